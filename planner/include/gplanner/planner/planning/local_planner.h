#pragma once
// Straight-line local planning: whether the motions between pairs of configurations are
// free, every motion sampled at a resolution and all samples of all motions checked in
// a few large batches.
//
// Resolution: by default as OMPL's DiscreteMotionValidator samples a motion in the
// equivalent compound state space (planner/ompl/state_space.h), so that comparisons
// with OMPL are like for like: every component (base position, base rotation, each
// joint) moves at most 1% of its own extent per segment (the base rotation's extent
// being a half turn). With `max_displacement` set, instead, no robot point moves
// farther than that per segment (MotionBound). Samples are visited coarse to fine (the midpoint,
// then the quarter points, ...), level by level across all motions: a motion found invalid drops
// out before its finer samples are checked, and once the samples left are few they all go in one
// batch, unless the levels are small enough for the checker to answer on the calling thread
// (CollisionChecker::cheap_calls_up_to): then level by level to the end, stopping at the
// first collision.
//
// Threads: check_motions and last_valid_fraction take calls from several threads at once
// (the OMPL motion validator's), each with its own samples, the checker taking concurrent
// calls; the statistics are added under a lock. set_stop and reset_stats are for the
// planner's own thread, not while calls run.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/motion_bound.h"
#include "gplanner/planner/planning/motion_checker.h"
#include "gplanner/planner/planning/timed_batch_size.h"
#include "gplanner/planner/scene/input_limits.h"  // kMaxEdgeSegments

namespace gplanner {

struct Scene;

struct LocalPlannerOptions {
  // Longest segment of each component as a fraction of that component's extent.
  double resolution_fraction = 0.01;
  // When > 0: the largest robot-point motion between samples, in metres (overrides
  // resolution_fraction).
  double max_displacement = 0;
  // Remaining samples at or below this many are checked in one batch.
  std::size_t one_batch_samples = 1 << 16;
  // No batch holds more samples than this (memory; and stop conditions are polled
  // between batches).
  std::size_t max_batch_samples = 1 << 18;
  // > 0: batches are also sized from the checker's measured throughput so that one
  // takes about this long (a planner's stop is then seen that often); 0: not by time.
  double batch_seconds = 0;
  // > 0, where calls cost nothing beyond their samples (the CPU backends): each level of
  // check_motions checks at least this many samples, more of each motion where few are
  // left (a shortcut's fine check: a few motions of hundreds of samples), so that every
  // call gives the host's threads work; the samples past a motion's first collision that
  // this checks are the price. The verdicts are the same. 0: one sample of each motion,
  // then two, four, ... (OMPL's order, for one motion at a time from a planner's thread).
  std::size_t least_level_samples = 0;
};

struct MotionCheckStats {
  std::size_t motions = 0;
  std::size_t samples = 0;  // samples checked
  std::size_t batches = 0;
};

class LocalPlanner : public MotionChecker {
 public:
  // `scene` and `checker` must outlive the planner.
  LocalPlanner(const Scene& scene, CollisionChecker* checker,
               const LocalPlannerOptions& options = {});

  // Segments the motion from a to b is cut into (at least 1); the samples are the
  // interior points j / segments for j = 1 .. segments - 1.
  int segments(const float* a, const float* b) const;

  // from, to: shape [count, width]; invalid: shape [count], set to 1 when some interior
  // sample of the motion collides, 0 otherwise. The endpoints are not checked: callers
  // check states in their own batches. Returns false, with `invalid` incomplete, when
  // the stop condition (set_stop) said to stop between two batches.
  bool check_motions(const float* from, const float* to, std::size_t count,
                     std::uint8_t* invalid) override;
  // The same with each motion's segment count given (shape [count]; e.g. another
  // planner's segments(), so that motions at two resolutions share one set of batches).
  bool check_motions(const float* from, const float* to, std::size_t count,
                     const int* segment_count, std::uint8_t* invalid);

  // Polled between batches of check_motions; true stops it. Empty: never stop.
  void set_stop(std::function<bool()> should_stop) { should_stop_ = std::move(should_stop); }

  // The samples of the motion, in order from a (exclusive) to b (inclusive), up to the
  // first collision (1, 2, 4, ... per call while the checker's calls stay cheap, then
  // the rest in one call; all in one call where no call is cheap or one_call is set):
  // the fraction of the way of the last valid sample before the first collision (0 when
  // the first sample collides), or 1 when all are free.
  double last_valid_fraction(const float* a, const float* b, bool one_call = false);
  // The same with the motion's segment count given (e.g. OMPL's validSegmentCount).
  double last_valid_fraction(const float* a, const float* b, int segments, bool one_call);

  // The checker's configurations_per_call_cost(), and the one-batch limit above.
  std::size_t configurations_per_call_cost() const {
    return checker_->configurations_per_call_cost();
  }
  std::size_t one_batch_samples() const { return options_.one_batch_samples; }

  // Of all calls so far (a copy: calls on other threads may be adding to them).
  MotionCheckStats stats() const;
  void reset_stats();
  const ConfigurationMetric& metric() const { return metric_; }

 private:
  // Segments by the components' own resolutions, before rounding up.
  double component_segments(const float* a, const float* b) const;
  void add_stats(std::size_t motions, std::size_t samples, std::size_t batches);

  const Scene& scene_;
  CollisionChecker* checker_;
  LocalPlannerOptions options_;
  ConfigurationMetric metric_;
  MotionBound bound_;
  mutable std::mutex stats_mutex_;
  MotionCheckStats stats_;  // under stats_mutex_
  std::function<bool()> should_stop_;
  TimedBatchSize batch_size_;  // samples per checker call
};

// The interior sample indices 1 .. segments - 1, coarse to fine: the midpoint first,
// then the midpoints of the halves, and so on (each index once).
std::vector<int> coarse_to_fine_order(int segments);

}  // namespace gplanner
