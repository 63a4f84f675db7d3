#include "apps/hostile/catalogue_case.h"

#include <cctype>
#include <set>
#include <stdexcept>

namespace gplanner::hostile {
namespace {

std::vector<std::string> strings(const YAML::Node& node) {
  std::vector<std::string> out;
  if (!node) return out;
  if (node.IsScalar()) return {node.as<std::string>()};
  for (const YAML::Node& item : node) out.push_back(item.as<std::string>());
  return out;
}

const std::set<std::string> kKinds = {
    "files destroyed",           "crashes",          "hangs/memory", "time limit",
    "late or misleading errors", "silently accepted"};

const std::set<std::string> kKeys = {
    "name",    "class",   "files", "args",     "exit", "message", "advice",       "outputs",
    "changes", "limit_s", "max_s", "non_root", "note", "absent",  "output_lacks", "output_yaml"};

CatalogueCase parse_case(const YAML::Node& entry) {
  CatalogueCase c;
  c.name = entry["name"].as<std::string>();
  for (const auto& key : entry) {
    if (!kKeys.count(key.first.as<std::string>()))
      throw std::runtime_error("unknown key '" + key.first.as<std::string>() + "'");
  }
  for (const char ch : c.name) {
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_')
      throw std::runtime_error("a name is letters, digits and underscores only");
  }
  c.kind = entry["class"].as<std::string>();
  if (!kKinds.count(c.kind)) throw std::runtime_error("unknown class '" + c.kind + "'");
  c.files = entry["files"] ? entry["files"] : YAML::Node(YAML::NodeType::Map);
  for (const YAML::Node& arg : entry["args"]) c.arguments.push_back(arg);
  if (entry["exit"].IsScalar()) {
    c.exit_codes = {entry["exit"].as<int>()};
  } else {
    for (const YAML::Node& code : entry["exit"]) c.exit_codes.push_back(code.as<int>());
  }
  if (c.exit_codes.empty()) throw std::runtime_error("no exit code");
  c.message = strings(entry["message"]);
  // Refusals say what to change; a legitimate run (0, 4) need not.
  const bool refused = c.exit_codes.size() == 1 && c.exit_codes[0] == 2;
  c.advice = entry["advice"] ? entry["advice"].as<bool>() : refused;
  if (refused && c.message.empty())
    throw std::runtime_error("a refusal must name its file or option");
  c.absent = strings(entry["absent"]);
  if (entry["output_lacks"]) c.output_lacks = entry["output_lacks"];
  c.output_yaml = strings(entry["output_yaml"]);
  c.outputs = strings(entry["outputs"]);
  c.changes = strings(entry["changes"]);
  if (entry["limit_s"]) c.limit_s = entry["limit_s"].as<double>();
  if (entry["max_s"]) c.max_s = entry["max_s"].as<double>();
  // A time-limit case is a hang a few seconds past its bound.
  if (c.max_s > 0 && !entry["limit_s"]) c.limit_s = c.max_s + 4;
  if (entry["non_root"]) c.needs_non_root = entry["non_root"].as<bool>();
  return c;
}

}  // namespace

std::vector<CatalogueCase> load_catalogue(const std::string& file) {
  const YAML::Node root = YAML::LoadFile(file);
  std::vector<CatalogueCase> cases;
  std::set<std::string> names;
  for (const YAML::Node& entry : root["cases"]) {
    const std::string where = file + ":" + std::to_string(entry.Mark().line + 1);
    try {
      cases.push_back(parse_case(entry));
    } catch (const std::exception& e) {
      throw std::runtime_error(where + ": " + e.what());
    }
    if (!names.insert(cases.back().name).second)
      throw std::runtime_error(where + ": a second case named " + cases.back().name);
  }
  return cases;
}

std::string build_text(const YAML::Node& spec, const std::string& folder) {
  std::string text;
  if (spec.IsScalar()) {
    text = spec.as<std::string>();
  } else if (spec["parts"]) {
    for (const YAML::Node& part : spec["parts"]) text += build_text(part, folder);
  } else {
    const std::string body = spec["text"] ? spec["text"].as<std::string>() : "";
    const long long repeat = spec["repeat"] ? spec["repeat"].as<long long>() : 1;
    if (spec["prefix"]) text += spec["prefix"].as<std::string>();
    text.reserve(text.size() + body.size() * repeat);
    for (long long i = 0; i < repeat; ++i) text += body;
    if (spec["suffix"]) text += spec["suffix"].as<std::string>();
  }
  for (std::size_t at = text.find("$DIR"); at != std::string::npos;
       at = text.find("$DIR", at + folder.size())) {
    text.replace(at, 4, folder);
  }
  return text;
}

}  // namespace gplanner::hostile
