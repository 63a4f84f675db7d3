#pragma once
// Typed values out of one YAML document, every problem an InputError with the file, the
// line and the key path: for the scene loader and gplan-bench's configurations (not
// installed: it needs yaml-cpp's headers).

#include <yaml-cpp/yaml.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/input_file.h"

namespace gplanner {

// Reads typed values out of one YAML document, turning every problem into an
// InputError with the file, the line and the key path ("robot.base_pose.xyz").
class YamlReader {
 public:
  explicit YamlReader(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  SourceLocation at(const YAML::Node& node, const std::string& key) const {
    const int line = node.IsDefined() && node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
    return {file_, line, key};
  }

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key,
                         const std::string& problem) const {
    throw InputError(at(node, key), problem);
  }

  // Requires a map whose keys are all in `allowed`; returns it.
  void expect_map(const YAML::Node& node, const std::string& key,
                  const std::set<std::string>& allowed) const {
    if (!node.IsMap()) fail(node, key, "expected a map of keys, found " + kind(node));
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) {
        fail(entry.first, key, "expected a key name, found " + kind(entry.first));
      }
      const std::string name = entry.first.as<std::string>();
      if (!allowed.count(name)) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(entry.first, join(key, name), "unknown key; expected one of: " + list);
      }
    }
  }

  YAML::Node required(const YAML::Node& map, const std::string& key,
                      const std::string& name) const {
    const YAML::Node value = map[name];
    if (!value) fail(map, join(key, name), "missing; add it");
    return value;
  }

  double number(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "expected a number, found " + kind(node));
    double value = 0;
    if (!YAML::convert<double>::decode(node, value)) {
      fail(node, key, "expected a number, found '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(node, key, "must be a finite number, not " + node.Scalar());
    return value;
  }

  // A whole number in [low, high].
  std::uint64_t whole_number(const YAML::Node& node, const std::string& key, std::uint64_t low,
                             std::uint64_t high) const {
    const double value = number(node, key);
    if (value != std::floor(value) || value < double(low) || value > double(high)) {
      fail(node, key,
           "expected a whole number from " + std::to_string(low) + " to " + std::to_string(high) +
               ", found '" + node.Scalar() + "'");
    }
    return static_cast<std::uint64_t>(value);
  }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "expected a string, found " + kind(node));
    return node.Scalar();
  }

  std::vector<double> numbers(const YAML::Node& node, const std::string& key,
                              std::size_t count) const {
    if (!node.IsSequence() || node.size() != count) {
      fail(node, key,
           "expected a list of " + std::to_string(count) + " numbers, found " + kind(node));
    }
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) {
      values.push_back(number(node[i], key + "[" + std::to_string(i) + "]"));
    }
    return values;
  }

  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& key) const {
    const std::vector<double> v = numbers(node, key, 3);
    return Eigen::Vector3d(v[0], v[1], v[2]);
  }

  Eigen::Quaterniond quaternion(const YAML::Node& node, const std::string& key) const {
    const std::vector<double> v = numbers(node, key, 4);
    // Divided by its largest part first, so that huge parts do not overflow the norm.
    double largest = 0;
    for (const double part : v) largest = std::max(largest, std::abs(part));
    if (largest < 1e-9) {
      fail(node, key, "zero-length quaternion; give [w, x, y, z] with w = 1 for no rotation");
    }
    return Eigen::Quaterniond(v[0] / largest, v[1] / largest, v[2] / largest, v[3] / largest)
        .normalized();
  }

  // A file named relative to the scene file: a readable regular file of `kind`.
  std::string path(const YAML::Node& node, const std::string& key,
                   const InputFileKind& kind) const {
    const std::string resolved = resolve(node, key);
    check_input_file(resolved, kind, at(node, key));
    return resolved;
  }

  // A folder named relative to the scene file.
  std::string folder(const YAML::Node& node, const std::string& key) const {
    const std::string resolved = resolve(node, key);
    std::error_code error;
    const std::filesystem::file_status status = std::filesystem::status(resolved, error);
    if (!std::filesystem::is_directory(status)) {
      const std::string problem = !std::filesystem::exists(status) ? "does not exist" : "is not a folder";
      fail(node, key,
           "'" + resolved + "' " + problem + (error ? " (" + error.message() + ")" : "") +
               "; fix the path (relative to the scene file)");
    }
    return resolved;
  }

  static std::string join(const std::string& key, const std::string& name) {
    return key.empty() ? name : key + "." + name;
  }

 private:
  std::string resolve(const YAML::Node& node, const std::string& key) const {
    return (std::filesystem::path(file_).parent_path() / text(node, key)).lexically_normal().string();
  }

  static std::string kind(const YAML::Node& node) {
    switch (node.Type()) {
      case YAML::NodeType::Null:
        return "nothing";
      case YAML::NodeType::Scalar:
        return "'" + node.Scalar() + "'";
      case YAML::NodeType::Sequence:
        return "a list of " + std::to_string(node.size());
      case YAML::NodeType::Map:
        return "a map";
      default:
        return "no value";
    }
  }

  std::string file_;
};

}  // namespace gplanner
