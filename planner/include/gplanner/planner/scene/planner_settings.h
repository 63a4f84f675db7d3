#pragma once
// Planner settings: the defaults of config/planner.yaml (built into the library) with a
// scene's overrides under `planner:`, typed. They are read and range-checked in one
// place (planner/src/scene/planner_settings.cpp, one table of key, member, range and
// message); the stages take the members.

#include <cstddef>
#include <cstdint>
#include <string>

namespace gplanner {

struct PlannerSettings {
  // The defaults of config/planner.yaml, as built into the library.
  PlannerSettings();

  std::uint64_t seed;   // random seed: sampling is deterministic for a given seed
  double time_limit_s;  // give up planning after this many seconds
  struct DistanceWeights {
    double position;  // per metre of base translation
    double rotation;  // per radian of base rotation angle
    double joint;     // per radian (or metre) of joint motion
  } distance_weights;
  double delta_fraction;    // tolerance band as a fraction of the scene's size, (0, 1e-5]
  double edge_resolution;   // edges sampled at this fraction of the space's extent
  double max_displacement;  // > 0: samples by robot-point motion instead (metres)
  struct Roadmap {
    std::size_t milestones;  // free milestones of the first round
    int neighbors;           // k of the k-NN
    int lazy_batch_paths;    // paths whose unknown edges lazy PRM checks in one batch
  } roadmap;
  struct Shortcut {
    int rounds;      // rounds of batched shortcutting (0: none)
    int candidates;  // shortcuts proposed per round
  } shortcut;
  struct Sampler {
    double rotation_spread;  // > 0: rotations drawn about the start-goal way
    double bridge_fraction;  // fraction of attempts by the bridge test
    double bridge_sigma;     // how far apart the bridge's ends are drawn
  } sampler;

  // The value of a setting by its key in config/planner.yaml ("roadmap.milestones");
  // throws std::out_of_range for a key it does not define.
  [[deprecated("read the typed member instead (since 0.2.0); to be removed in 0.6")]] double number(
      const std::string& key) const;

 private:
  struct Unset {};
  explicit PlannerSettings(Unset) {}
  friend const PlannerSettings& built_in_planner_settings();
};

// The text of config/planner.yaml as built into the library.
const char* default_planner_settings_yaml();

}  // namespace gplanner
