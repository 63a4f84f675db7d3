#include "harness/broad_phase_config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/planner/scene/yaml_reader.h"

namespace gplan {
namespace {

using gplanner::YamlReader;

std::string method_list() {
  std::string list;
  for (const gplanner::BroadPhaseMethod m : gplanner::broad_phase_methods())
    list += (list.empty() ? "" : ", ") + std::string(gplanner::broad_phase_method_name(m));
  return list;
}

std::string method_name(const YamlReader& in, const YAML::Node& node, const std::string& key) {
  const std::string name = in.text(node, key);
  gplanner::BroadPhaseMethod method{};
  if (!gplanner::parse_broad_phase_method(name, &method))
    in.fail(node, key, "'" + name + "' is not one of " + method_list());
  return name;
}

// A number in (low, high].
double above(const YamlReader& in, const YAML::Node& node, const std::string& key, double low,
             double high, const std::string& what) {
  const double value = in.number(node, key);
  if (!(value > low && value <= high)) {
    std::ostringstream range;
    range << "expected " << what << " above " << low << " and at most " << high << ", found '"
          << node.Scalar() << "'";
    in.fail(node, key, range.str());
  }
  return value;
}

}  // namespace

const std::vector<std::string>& broad_phase_keys() {
  static const std::vector<std::string> keys = {"methods", "counts",          "max_count",
                                                "frames",  "min_frames",      "count_budget",
                                                "radius",  "volume_fraction", "speed"};
  return keys;
}

BroadPhaseOptions read_broad_phase_options(const YamlReader& in, const YAML::Node& root) {
  BroadPhaseOptions o;
  const YAML::Node methods = in.required(root, "", "methods");
  if (!methods.IsSequence() || methods.size() == 0)
    in.fail(methods, "methods",
            "expected a list of methods (one or more of: " + method_list() + ")");
  for (std::size_t i = 0; i < methods.size(); ++i) {
    const std::string key = "methods[" + std::to_string(i) + "]";
    const std::string name = method_name(in, methods[i], key);
    if (std::find(o.methods.begin(), o.methods.end(), name) != o.methods.end())
      in.fail(methods[i], key, "'" + name + "' is listed twice; list it once");
    o.methods.push_back(name);
  }
  const YAML::Node counts = in.required(root, "", "counts");
  if (!counts.IsSequence() || counts.size() == 0)
    in.fail(counts, "counts", "expected a list of sphere counts, e.g. [64, 128, 192, 256, 320]");
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const std::string key = "counts[" + std::to_string(i) + "]";
    const std::uint64_t n = in.whole_number(counts[i], key, 2, 100000000);
    if (std::find(o.counts.begin(), o.counts.end(), n) != o.counts.end())
      in.fail(counts[i], key, "'" + counts[i].Scalar() + "' is listed twice; list it once");
    o.counts.push_back(n);
  }
  std::sort(o.counts.begin(), o.counts.end());
  if (const YAML::Node caps = root["max_count"]) {
    if (!caps.IsMap())
      in.fail(caps, "max_count",
              "expected a map of METHOD: largest count, e.g. {cpu-all-pairs: 20000}");
    for (const auto& entry : caps) {
      const std::string key = "max_count." + entry.first.Scalar();
      const std::string name = method_name(in, entry.first, key);
      if (std::find(o.methods.begin(), o.methods.end(), name) == o.methods.end())
        in.fail(entry.first, key,
                "'" + name + "' is not in methods; add it there or leave it out here");
      o.max_count[name] = in.whole_number(entry.second, key, 2, 100000000);
    }
  }
  if (root["frames"]) o.frames = int(in.whole_number(root["frames"], "frames", 1, 1000000));
  if (root["min_frames"])
    o.min_frames = int(in.whole_number(root["min_frames"], "min_frames", 1, 1000000));
  if (o.min_frames > o.frames) {
    in.fail(root["min_frames"], "min_frames",
            "is more than frames (" + std::to_string(o.frames) + "); make it at most that");
  }
  if (root["count_budget"])
    o.count_budget_s = above(in, root["count_budget"], "count_budget", 0, 86400, "seconds");
  if (const YAML::Node radius = root["radius"]) {
    if (radius.IsSequence()) {
      const std::vector<double> r = in.numbers(radius, "radius", 2);
      o.radius_min = r[0];
      o.radius_max = r[1];
    } else {
      o.radius_min = o.radius_max = in.number(radius, "radius");
    }
    if (!(o.radius_min > 0 && o.radius_min <= o.radius_max && o.radius_max <= 1e6)) {
      in.fail(radius, "radius",
              "expected a radius above 0 (at most 1e6), or [min, max] with 0 < min <= max");
    }
  }
  if (root["volume_fraction"]) {
    o.volume_fraction = above(in, root["volume_fraction"], "volume_fraction", 0, 0.5,
                              "a fraction of the box's volume");
  }
  if (root["speed"]) o.speed = above(in, root["speed"], "speed", 0, 1000, "mean radii per frame");
  return o;
}

}  // namespace gplan
