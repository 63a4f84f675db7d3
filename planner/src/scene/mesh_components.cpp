#include "gplanner/planner/scene/mesh_components.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace gplanner {
namespace {

struct PositionHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::size_t h = 0;
    for (int k = 0; k < 3; ++k) {
      const double v = p[k] + 0.0;  // -0 and +0 are one position
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof(bits));
      h = h * 1000003u ^ std::hash<std::uint64_t>()(bits);
    }
    return h;
  }
};
struct PositionEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
  }
};

int find(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

}  // namespace

MeshComponents mesh_components(const TriangleMesh& mesh, const std::vector<std::uint8_t>& labels) {
  MeshComponents out;
  const std::size_t n = mesh.triangles.size();
  // Welded vertex of each mesh vertex.
  std::unordered_map<Eigen::Vector3d, int, PositionHash, PositionEqual> weld;
  std::vector<int> welded(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    welded[v] = weld.emplace(mesh.vertices[v], static_cast<int>(weld.size())).first->second;
  // Union-find over (welded vertex, label): triangles of different labels never join.
  const int positions = static_cast<int>(weld.size());
  const auto node = [&](std::size_t t, int k) {
    return welded[mesh.triangles[t][k]] + (labels.empty() || !labels[t] ? 0 : positions);
  };
  std::vector<int> parent(static_cast<std::size_t>(positions) * (labels.empty() ? 1 : 2));
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t t = 0; t < n; ++t) {
    const int a = find(parent, node(t, 0));
    for (int k = 1; k < 3; ++k) {
      const int b = find(parent, node(t, k));
      if (a != b) parent[b] = a;
    }
  }
  std::unordered_map<int, int> component_of_root;
  out.of_triangle.resize(n);
  for (std::size_t t = 0; t < n; ++t) {
    const int root = find(parent, node(t, 0));
    out.of_triangle[t] =
        component_of_root.emplace(root, static_cast<int>(component_of_root.size())).first->second;
  }
  out.count = static_cast<int>(component_of_root.size());

  // Directed edges between union-find nodes (so components never share one), sorted,
  // so that equal edges lie together and the example edge a message names is the same
  // from run to run.
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * n);
  std::vector<std::uint8_t> has_area(out.count, 0);
  for (std::size_t t = 0; t < n; ++t) {
    const int v[3] = {node(t, 0), node(t, 1), node(t, 2)};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
    has_area[out.of_triangle[t]] = 1;
    for (int k = 0; k < 3; ++k) edges.push_back(key(v[k], v[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  const auto count_of = [&](std::uint64_t e) {
    const auto range = std::equal_range(edges.begin(), edges.end(), e);
    return range.second - range.first;
  };
  out.closed.assign(out.count, 1);
  for (int c = 0; c < out.count; ++c)
    if (!has_area[c]) out.closed[c] = 0;
  // Each directed edge without exactly one opposite, or appearing more than once.
  std::vector<Eigen::Vector3d> position(positions);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) position[welded[v]] = mesh.vertices[v];
  std::vector<std::size_t> unmatched(out.count, 0);
  bool example = false;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t end = i + 1;
    while (end < edges.size() && edges[end] == edges[i]) ++end;
    const std::uint64_t edge = edges[i];
    const int a = static_cast<int>(edge >> 32), b = static_cast<int>(edge & 0xffffffffu);
    const bool matched = end - i == 1 && count_of(key(b, a)) == 1;
    i = end;
    if (matched) continue;
    const int c = component_of_root.at(find(parent, a));
    out.closed[c] = 0;
    ++unmatched[c];
    if (!example) {
      example = true;
      out.open_edge_from = position[a % positions];
      out.open_edge_to = position[b % positions];
    }
  }
  for (int c = 0; c < out.count; ++c) {
    if (out.closed[c]) continue;
    ++out.open_count;
    out.unmatched_edges += unmatched[c];
  }
  return out;
}

std::vector<std::uint8_t> closed_triangles(const MeshComponents& components) {
  std::vector<std::uint8_t> solid(components.of_triangle.size());
  for (std::size_t t = 0; t < solid.size(); ++t)
    solid[t] = components.closed[components.of_triangle[t]];
  return solid;
}

std::string describe_open_components(const MeshComponents& c) {
  std::ostringstream text;
  text << c.open_count << " of " << c.count << " connected component" << (c.count == 1 ? "" : "s")
       << (c.open_count == 1 ? " is" : " are") << " open (" << c.unmatched_edges << " edge"
       << (c.unmatched_edges == 1 ? "" : "s") << " without exactly one opposite edge";
  if (c.unmatched_edges > 0) {
    text << ", e.g. the edge from (" << c.open_edge_from.x() << ", " << c.open_edge_from.y() << ", "
         << c.open_edge_from.z() << ") to (" << c.open_edge_to.x() << ", " << c.open_edge_to.y()
         << ", " << c.open_edge_to.z() << ")";
  }
  text << ")";
  return text.str();
}

}  // namespace gplanner
