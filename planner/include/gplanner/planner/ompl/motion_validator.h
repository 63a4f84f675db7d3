#pragma once
// An OMPL motion validator backed by any of our collision backends: the straight-line
// motion between two states (the end state included, the start assumed valid, as
// OMPL's DiscreteMotionValidator does), certified by default (below), or sampled at the
// scene's edge resolution. Sampled, as
// OMPL's, a single motion is checked end state first, then coarse to fine (the
// midpoint, the quarter points, ...), stopping at the first collision; with lastValid,
// in order from the start. Small calls are answered on the host (the calling thread,
// or the thread pool where it pays: CollisionChecker::host_checker), so one motion costs
// what its samples cost.
// Keeps OMPL's valid and invalid motion counters.
// Calls from any number of threads run at once, each with its own samples (every
// backend takes concurrent calls; see collision_checker.h for which run in parallel);
// only the counters are updated under a lock. The batch extension checks many motions
// in one call, level by level (LocalPlanner::check_motions).
//
// Certified (EdgeChecks::kCertified, the default since 0.2.0): every motion is certified
// free along its whole length (CertifiedMotions), not sampled; a motion that is not
// certified is invalid, and its last valid state is the last sample before the first
// collision if the motion up to it certifies, else the start state. Sampled
// (EdgeChecks::kSampled, or given LocalPlannerOptions) is what OMPL's
// DiscreteMotionValidator does: faster, and blind to a wall thinner than the samples'
// spacing.

#include <ompl/base/MotionValidator.h>

#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/plan_options.h"

namespace gplanner {

struct Scene;

namespace ompl_adapters {

class MotionValidator : public ompl::base::MotionValidator {
 public:
  // scene and checker must outlive this object. By default every motion is certified
  // free along its whole length (since 0.2.0; before, sampled: a motion free at its
  // samples can cross a wall thinner than their spacing).
  MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                  CollisionChecker* checker);
  // Sampled, at `options`' resolution (the scene's edge_resolution and max_displacement
  // where not given).
  MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                  CollisionChecker* checker, const LocalPlannerOptions& options);
  // Sampled at the scene's resolution, or certified (with `certified`'s step).
  MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                  CollisionChecker* checker, EdgeChecks edges,
                  const CertifiedMotionOptions& certified = {});

  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

  // valid[i] = 1 when the motion motions[i].first -> motions[i].second is valid; every
  // motion's samples in a few large batches, the end states in one more.
  void checkMotions(
      const std::vector<std::pair<const ompl::base::State*, const ompl::base::State*>>& motions,
      std::vector<std::uint8_t>* valid) const;

  // Adds motions checked elsewhere (our planners' edges) to OMPL's counters, under the
  // lock that calls on other threads take.
  void add_counts(std::size_t valid, std::size_t invalid) const { count(valid, invalid); }

 private:
  // Adds to OMPL's counters (valid_, invalid_), which calls on other threads update too.
  void count(std::size_t valid, std::size_t invalid) const;
  // Certified: whether the motion a -> b (rows) is certified free.
  bool certified_free(const float* a, const float* b) const;
  // Sampled: whether the motion a -> b (segments long) is free, its end included, in the
  // way that has cost less on this scene so far (ChoiceOfWay).
  bool sampled_free(const float* a, const float* b, int segments) const;
  // The segments a motion is sampled in: OMPL's validSegmentCount, so that a resolution
  // the user sets on the space information (setStateValidityCheckingResolution) is
  // followed as OMPL's own validators follow it; the local planner's own count where it
  // was given options, or the scene bounds robot-point motion (max_displacement).
  int segments(const ompl::base::State* s1, const ompl::base::State* s2, const float* a,
               const float* b) const;

  const Scene& scene_;
  CollisionChecker* checker_;
  mutable std::mutex counters_mutex_;
  mutable LocalPlanner local_;  // takes concurrent calls
  // The same on the checker's host checks (single motions level by level).
  mutable LocalPlanner host_local_;
  EdgeChecks edges_ = EdgeChecks::kSampled;
  bool follows_space_resolution_ = true;  // segments(): OMPL's count
  mutable CertifiedMotions certifier_;    // takes concurrent calls

  // A single motion on a checker with a fixed cost per call (the gpu backend): its end
  // state on the host first (most motions an RRT tries end in collision), then, where the
  // end is free, the samples between one of two ways: level by level up to the first
  // collision, every level on the host (CollisionChecker::host_checker: the calling
  // thread, the pool for levels where it is faster), or all in one call (routed: one GPU
  // call where the motion has more samples than the host's crossover). Which costs less
  // depends on the robot and on how often motions collide early, so both are timed on the
  // calls themselves: the way with the lower running mean is taken, the other every 16th
  // call.
  struct ChoiceOfWay {
    std::mutex mutex;
    double mean_seconds[2] = {0, 0};  // [levels, one call]
    std::size_t timed[2] = {0, 0};
    std::size_t calls = 0;
  };
  mutable ChoiceOfWay way_;
};

}  // namespace ompl_adapters
}  // namespace gplanner
