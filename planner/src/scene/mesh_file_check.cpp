#include "mesh_file_check.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "gplanner/planner/scene/input_file.h"

namespace gplanner {
namespace {

constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

// The first `count` bytes of `path`.
std::string file_head(const std::string& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string head(count, '\0');
  in.read(head.data(), static_cast<std::streamsize>(count));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

// Bytes of one PLY scalar type in a binary file; 0 for an unknown type.
std::uint64_t ply_type_bytes(const std::string& type) {
  static const std::map<std::string, std::uint64_t> sizes = {
      {"char", 1},   {"int8", 1},    {"uchar", 1},  {"uint8", 1},   {"short", 2},
      {"int16", 2},  {"ushort", 2},  {"uint16", 2}, {"int", 4},     {"int32", 4},
      {"uint", 4},   {"uint32", 4},  {"float", 4},  {"float32", 4}, {"double", 8},
      {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

// A PLY header's elements: each count must fit the bytes after the header, each element
// taking at least its scalar properties' bytes and its lists' counts (binary), or two
// characters a property (ASCII: a digit and a separator), and at least one byte.
void check_ply(const std::string& path, std::uintmax_t size, const SourceLocation& where,
               const std::string& what) {
  const std::string head = file_head(path, kMaxPlyHeaderBytes);
  const std::size_t end = head.find("end_header");
  if (end == std::string::npos) {
    throw InputError(where, what + " is a PLY file without an end_header line in its first " +
                                std::to_string(kMaxPlyHeaderBytes / 1024) +
                                " KiB; repair the header");
  }
  const std::size_t header_end = head.find('\n', end);
  const std::uint64_t body =
      size - std::min<std::uint64_t>(size, header_end == std::string::npos ? end : header_end + 1);
  std::istringstream lines(head.substr(0, end));
  std::string line;
  bool ascii = true;
  struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t min_bytes = 0;
  };
  std::vector<Element> elements;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> word;
      ascii = word == "ascii";
    } else if (word == "element") {
      Element element;
      words >> element.name >> element.count;
      if (words.fail()) {
        throw InputError(where, what + ": PLY header line '" + line +
                                    "' is not 'element NAME COUNT'; repair the header");
      }
      elements.push_back(element);
    } else if (word == "property" && !elements.empty()) {
      std::string type;
      words >> type;
      std::uint64_t bytes = 2;
      if (type == "list") words >> type;  // the count's type: a list holds at least that
      if (!ascii) bytes = ply_type_bytes(type);
      elements.back().min_bytes += bytes;
    }
  }
  long double needed = 0;
  for (const Element& element : elements) {
    needed += static_cast<long double>(element.count) *
              static_cast<long double>(std::max<std::uint64_t>(1, element.min_bytes));
    if (needed > static_cast<long double>(body)) {
      throw InputError(where, what + ": its PLY header claims " + std::to_string(element.count) +
                                  " " + element.name + " elements, more than the " +
                                  std::to_string(body) +
                                  " bytes after the header can hold; the header is wrong or "
                                  "the file cut short: repair or re-export the mesh");
    }
  }
}

// One COLLADA <node>: its line and the nodes it holds or instances.
struct ColladaNode {
  std::string id;
  int line = 0;
  std::vector<int> children;
  std::vector<std::string> instanced;  // ids of <instance_node url="#id">
};

void collect_nodes(const tinyxml2::XMLElement* element, int parent,
                   std::vector<ColladaNode>* nodes) {
  for (const tinyxml2::XMLElement* e = element->FirstChildElement(); e;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "node") {
      ColladaNode node;
      node.id = e->Attribute("id") ? e->Attribute("id") : "";
      node.line = e->GetLineNum();
      nodes->push_back(node);
      const int index = static_cast<int>(nodes->size()) - 1;
      if (parent >= 0) (*nodes)[parent].children.push_back(index);
      collect_nodes(e, index, nodes);
    } else if (tag == "instance_node" && parent >= 0) {
      const char* url = e->Attribute("url");
      if (url && url[0] == '#') (*nodes)[parent].instanced.push_back(url + 1);
      collect_nodes(e, parent, nodes);
    } else {
      collect_nodes(e, parent, nodes);
    }
  }
}

// The node tree assimp would build: no <instance_node> cycle, at most kMaxColladaNodes
// nodes, kMaxColladaDepth deep.
void check_collada(const std::string& path, const SourceLocation& where,
                   const std::string& what) {
  tinyxml2::XMLDocument doc;
  if (doc.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS) {
    throw InputError(where, what + " is not well-formed XML (line " +
                                std::to_string(doc.ErrorLineNum()) + ": " + doc.ErrorName() +
                                "); repair or re-export the COLLADA file");
  }
  std::vector<ColladaNode> nodes;
  collect_nodes(doc.RootElement(), -1, &nodes);
  std::map<std::string, int> by_id;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (!nodes[n].id.empty()) by_id.emplace(nodes[n].id, static_cast<int>(n));
  }
  std::vector<std::vector<int>> edges(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    edges[n] = nodes[n].children;
    for (const std::string& id : nodes[n].instanced) {
      const auto it = by_id.find(id);
      if (it != by_id.end()) edges[n].push_back(it->second);
    }
  }
  // Depth-first, without recursion: the size and depth of each node's expanded tree.
  enum State : char { kNew, kOpen, kDone };
  std::vector<State> state(nodes.size(), kNew);
  std::vector<std::uint64_t> expanded(nodes.size(), 1);
  std::vector<int> depth(nodes.size(), 1);
  auto where_node = [&](int n) {
    return what + ": COLLADA node '" + nodes[n].id + "' (line " + std::to_string(nodes[n].line) +
           ")";
  };
  for (std::size_t root = 0; root < nodes.size(); ++root) {
    if (state[root] != kNew) continue;
    std::vector<std::pair<int, std::size_t>> stack{{static_cast<int>(root), 0}};
    state[root] = kOpen;
    while (!stack.empty()) {
      auto& [n, next] = stack.back();
      if (next < edges[n].size()) {
        const int child = edges[n][next++];
        if (state[child] == kOpen) {
          throw InputError(where, where_node(child) +
                                      " instances itself through <instance_node> (a cycle); "
                                      "remove the cycle from the file");
        }
        if (state[child] == kNew) {
          state[child] = kOpen;
          stack.emplace_back(child, 0);
        }
        continue;
      }
      for (const int child : edges[n]) {
        expanded[n] = std::min(expanded[n] + expanded[child], kMaxColladaNodes + 1);
        depth[n] = std::max(depth[n], depth[child] + 1);
      }
      if (expanded[n] > kMaxColladaNodes) {
        throw InputError(where, where_node(n) + " expands through <instance_node> to more than " +
                                    std::to_string(kMaxColladaNodes) +
                                    " nodes; instance fewer nodes or merge them");
      }
      if (depth[n] > kMaxColladaDepth) {
        throw InputError(where, where_node(n) + " nests nodes more than " +
                                    std::to_string(kMaxColladaDepth) +
                                    " deep; flatten the node hierarchy");
      }
      state[n] = kDone;
      stack.pop_back();
    }
  }
}

bool has_dae_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".dae";
}

}  // namespace

void check_mesh_file(const std::string& path, std::uintmax_t size, const SourceLocation& where,
                     const std::string& what) {
  const std::string head = file_head(path, 512);
  if (head.rfind("ply", 0) == 0 && (head.size() == 3 || head[3] == '\n' || head[3] == '\r')) {
    check_ply(path, size, where, what);
  } else if (head.find("<COLLADA") != std::string::npos || has_dae_extension(path)) {
    check_collada(path, where, what);
  }
}

}  // namespace gplanner
