#pragma once
// Milestone sampling for the roadmap planners: candidates drawn in batches and checked
// in one batch call (two with the bridge test). Uniform within bounds and limits by
// default; for narrow passages, two options (OMPL users know the first as its
// BridgeTestValidStateSampler):
// - the bridge test (Hsu et al. 2003): a configuration q1 and a second one q2 drawn
//   about it; when both collide and their midpoint is free, the midpoint is a milestone.
//   It puts milestones in slots between obstacles (a doorway, a hole), where uniform
//   samples are rare, and none in the open;
// - rotations drawn about those on the way from the start's orientation to the goal's
//   instead of uniformly: where the passage admits only orientations within a fraction
//   of a degree of one (a piano tilted to its least width, a peg upright), a uniform
//   rotation almost never fits.

#include <cstddef>
#include <random>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/configuration_space.h"

namespace gplanner {

struct PlannerSettings;
struct PlanTimes;

struct SamplerOptions {
  // > 0: the rotation of a floating base is one on the shortest way from the start's to
  // the goal's (uniformly along it) turned by a rotation vector with this standard
  // deviation per axis, in radians (a planar base's angle likewise); 0: uniform.
  double rotation_spread = 0;
  // Fraction of the candidates drawn by the bridge test; the others are drawn alone.
  double bridge_fraction = 0;
  // The bridge's second end, q2, is q1 moved by a Gaussian of this standard deviation
  // under the planner's metric: per position axis sigma / position weight metres, a
  // rotation vector of sigma / rotation weight radians per axis, per joint
  // sigma / joint weight (sigma itself where a weight is 0); kept within bounds.
  double bridge_sigma = 0.05;
};

// The sampler options of a scene's planner settings (sampler.*).
SamplerOptions sampler_options(const PlannerSettings& settings);

class MilestoneSampler {
 public:
  // `space` must outlive the sampler.
  MilestoneSampler(const ConfigurationSpace& space, const ConfigurationMetric& metric,
                   const SamplerOptions& options);

  // The configurations whose orientations rotation_spread draws between (each shape
  // [width]).
  void set_endpoints(const float* start, const float* goal);

  // Attempts are drawn in streams of kStreamAttempts, each from a generator of its own
  // seeded by one draw of `rng` when the stream begins, so that many streams are drawn at
  // once on the host's threads. The milestones depend on the seed and the order of the
  // attempts alone: neither on how the attempts are split into calls, nor on the threads.
  static constexpr std::size_t kStreamAttempts = 1024;

  // Makes `attempts` attempts (a candidate, or a bridge), checks them and appends the
  // free milestones found to *found (shape [*, width]) in the order of the attempts.
  // Returns the number of configurations checked; adds the time taken to
  // times->sampling and times->state_checks.
  std::size_t sample(std::mt19937_64* rng, std::size_t attempts, CollisionChecker* checker,
                     std::vector<float>* found, PlanTimes* times);

  const SamplerOptions& options() const { return options_; }
  // One candidate as sample() draws it alone (uniform, or with rotation_spread), not
  // checked: written to q (shape [width]).
  void draw(std::mt19937_64* rng, float* q) const;

 private:
  void perturb(std::mt19937_64* rng, const float* q1, float* q2) const;
  // One attempt's candidates (one, or a bridge's two) appended to *q; whether a bridge.
  bool attempt(std::mt19937_64* rng, std::vector<float>* q) const;

  const ConfigurationSpace& space_;
  ConfigurationMetric metric_;
  SamplerOptions options_;
  std::vector<float> start_, goal_;
  // The stream under way: its generator, and the attempts it has left.
  std::mt19937_64 stream_;
  std::size_t stream_left_ = 0;
};

}  // namespace gplanner
