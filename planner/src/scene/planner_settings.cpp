#include "gplanner/planner/scene/planner_settings.h"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include "gplanner/planner/scene/input_limits.h"
#include "planner_settings_reader.h"

namespace gplanner {
namespace {

// One setting: its key in config/planner.yaml and a scene's `planner:`, the member it
// sets, its range and what to say when a value is outside it.
struct Setting {
  const char* key;
  double (*get)(const PlannerSettings&);
  void (*set)(PlannerSettings*, double);
  double low, high;
  bool low_open;  // low itself excluded
  bool whole;     // a whole number
  const char* what;
};

#define GPLANNER_SETTING(key, member, ...)                                                     \
  Setting {                                                                                    \
    key, [](const PlannerSettings& s) { return static_cast<double>(s.member); },               \
        [](PlannerSettings* s, double v) { s->member = static_cast<decltype(s->member)>(v); }, \
        __VA_ARGS__                                                                            \
  }

// Every setting, in the order config/planner.yaml gives them (the order values are
// checked in).
const Setting kSettings[] = {
    GPLANNER_SETTING("seed", seed, 0, 9007199254740992.0, false, true,
                     "must be a whole number from 0 to 9007199254740992 (2^53)"),
    GPLANNER_SETTING("time_limit_s", time_limit_s, 0, 1e9, true, false,
                     "must be a positive number of seconds"),
    GPLANNER_SETTING("distance_weights.position", distance_weights.position, 0, 1e9, false, false,
                     "must be 0 or more"),
    GPLANNER_SETTING("distance_weights.rotation", distance_weights.rotation, 0, 1e9, false, false,
                     "must be 0 or more"),
    GPLANNER_SETTING("distance_weights.joint", distance_weights.joint, 0, 1e9, false, false,
                     "must be 0 or more"),
    GPLANNER_SETTING("delta_fraction", delta_fraction, 0, 1e-5, true, false,
                     "must lie in (0, 1e-5]: the tolerance band may not exceed 1e-5 of the "
                     "scene's size"),
    GPLANNER_SETTING("edge_resolution", edge_resolution, 1.0 / kMaxEdgeSegments, 1, false, false,
                     "must lie in [1e-5, 1]: an edge across the space takes up to 1 / "
                     "edge_resolution samples, 1e5 at most"),
    GPLANNER_SETTING("max_displacement", max_displacement, 0, 1e9, false, false,
                     "must be 0 (off) or a distance in metres"),
    GPLANNER_SETTING("roadmap.milestones", roadmap.milestones, 1, 1e8, false, true,
                     "must be a whole number from 1 to 1e8"),
    GPLANNER_SETTING("roadmap.neighbors", roadmap.neighbors, 1, 64, false, true,
                     "must be a whole number from 1 to 64"),
    GPLANNER_SETTING("roadmap.lazy_batch_paths", roadmap.lazy_batch_paths, 1, 4096, false, true,
                     "must be a whole number from 1 to 4096"),
    GPLANNER_SETTING("shortcut.rounds", shortcut.rounds, 0, 1000, false, true,
                     "must be a whole number from 0 to 1000"),
    GPLANNER_SETTING("shortcut.candidates", shortcut.candidates, 1, 1e6, false, true,
                     "must be a whole number from 1 to 1e6"),
    GPLANNER_SETTING("sampler.rotation_spread", sampler.rotation_spread, 0, 1e9, false, false,
                     "must be 0 (uniform rotations) or a spread in radians"),
    GPLANNER_SETTING("sampler.bridge_fraction", sampler.bridge_fraction, 0, 1, false, false,
                     "must lie in [0, 1]"),
    GPLANNER_SETTING("sampler.bridge_sigma", sampler.bridge_sigma, 0, 1e9, true, false,
                     "must be a positive distance"),
};

#undef GPLANNER_SETTING

const Setting* find_setting(const std::string& key) {
  for (const Setting& s : kSettings)
    if (key == s.key) return &s;
  return nullptr;
}

bool in_range(const Setting& s, double v) {
  return (s.low_open ? v > s.low : v >= s.low) && v <= s.high && (!s.whole || v == std::floor(v));
}

// Walks a map of settings (nested maps joined with dots), handing each leaf's key and
// node to `leaf`; `key` is the path of `node` ("" at the top).
void for_each_leaf(
    const YAML::Node& node, const std::string& key,
    const std::function<void(const std::string&, const YAML::Node&, const YAML::Node&)>& leaf) {
  for (const auto& entry : node) {
    const std::string name = YamlReader::join(key, entry.first.as<std::string>());
    if (entry.second.IsMap()) {
      for_each_leaf(entry.second, name, leaf);
    } else {
      leaf(name, entry.first, entry.second);
    }
  }
}

}  // namespace

// config/planner.yaml, read once: every key of the table given there, none other, each
// value within its range (a mistake there is the build's, not the user's).
const PlannerSettings& built_in_planner_settings() {
  static const PlannerSettings defaults = [] {
    PlannerSettings settings{PlannerSettings::Unset{}};
    const YamlReader in("config/planner.yaml (built in)");
    std::size_t given = 0;
    for_each_leaf(YAML::Load(default_planner_settings_yaml()), "",
                  [&](const std::string& key, const YAML::Node&, const YAML::Node& value) {
                    const Setting* s = find_setting(key);
                    const double v = in.number(value, key);
                    if (s == nullptr || !in_range(*s, v))
                      throw std::logic_error(
                          "config/planner.yaml (built in): " + key +
                          (s ? std::string(": ") + s->what : std::string(": not a setting")));
                    s->set(&settings, v);
                    ++given;
                  });
    if (given != sizeof(kSettings) / sizeof(kSettings[0]))
      throw std::logic_error("config/planner.yaml (built in) leaves settings out");
    return settings;
  }();
  return defaults;
}

PlannerSettings::PlannerSettings() : PlannerSettings(built_in_planner_settings()) {}

double PlannerSettings::number(const std::string& key) const {
  const Setting* s = find_setting(key);
  if (s == nullptr) throw std::out_of_range("no planner setting '" + key + "'");
  return s->get(*this);
}

PlannerSettings read_planner_settings(const YamlReader& in, const YAML::Node& overrides) {
  PlannerSettings settings = built_in_planner_settings();
  if (!overrides) return settings;
  if (!overrides.IsMap()) in.fail(overrides, "planner", "expected a map of settings");
  // Each value read (a known key, a number), then each checked against its range in the
  // table's order before it is set.
  struct Given {
    const Setting* setting;
    double value;
    YAML::Node node;
  };
  std::vector<Given> given;
  for_each_leaf(overrides, "planner",
                [&](const std::string& name, const YAML::Node& key, const YAML::Node& value) {
                  const Setting* s = find_setting(name.substr(std::string("planner.").size()));
                  if (s == nullptr)
                    in.fail(key, name, "unknown planner setting; config/planner.yaml lists them");
                  given.push_back({s, in.number(value, name), value});
                });
  for (const Setting& s : kSettings) {
    for (const Given& g : given) {
      if (g.setting != &s) continue;
      if (!in_range(s, g.value)) in.fail(g.node, std::string("planner.") + s.key, s.what);
      s.set(&settings, g.value);
    }
  }
  return settings;
}

}  // namespace gplanner
