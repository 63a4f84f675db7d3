#pragma once
// Motions certified free: an answer that holds for every configuration on the straight
// motion, not only at samples.
//
// MotionBound bounds, per robot link, how far its points move along a motion, each
// link's bound adding to its parent's. Cut a motion into segments; a configuration
// inside a segment lies within half the segment of one of its two ends, so every point
// of link l is within c_l = half l's bound over the segment of where it is at that end.
// If at both ends link l keeps a clearance c_l to the environment, and each checked link
// pair (a, b) a clearance c_a + c_b - 2 c_h (h the deepest link both hang from:
// c_a - c_h bounds how far a's points move relative to h, so the two approach each other
// by at most that sum), no configuration of the segment brings any checked pair into
// contact (CollisionChecker::check_clearances). Segments start so that no link moves
// farther than `step` along one. Each round checks, in one batch, the ends of every open
// segment not yet known to keep their clearance (ends shared by two segments once); an end
// that fails but is free itself (check()) halves its segment for the next round, whose
// clearances are half as large, so that segments near obstacles are refined and those far
// from them are not; an end that collides makes the motion invalid. Where the checker's
// calls have a fixed cost (the GPU's), a round is one call and segments are cut into
// quarters instead: the plain checks go in the same call as the clearances where they
// add fewer rows than a call costs, else those of the failing ends in the next round's
// call. A segment that would be halved below `finest_step` makes its motion invalid too:
// certified answers are conservative.
//
// With the tolerance band: the clearances are added to the checker's own leaf threshold,
// which stays there to absorb float rounding (docs/design.md, "The tolerance band");
// "certified free" means that no configuration on the motion brings any checked pair
// closer than 0 (FCL's distance), up to that band; a motion within the band of contact
// may be reported invalid, never the other way round.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/motion_bound.h"
#include "gplanner/planner/planning/motion_checker.h"
#include "gplanner/planner/planning/timed_batch_size.h"

namespace gplanner {

struct Scene;

struct CertifiedMotionOptions {
  // Metres: along the first segments of a motion no link moves farther than this. <= 0:
  // 1 % of the robot's size (ToleranceBand::robot_size), or 1 % of the longest motion
  // the space allows (MotionBound::longest_displacement) where that is less.
  double step = 0;
  // Metres: a segment not certified when its bound is below this makes its motion
  // invalid. <= 0: step / 1024.
  double finest_step = 0;
  // > 0: each round's ends are checked in calls sized from the checker's measured
  // throughput to take about this long, the stop condition polled between them (as
  // LocalPlannerOptions::batch_seconds); 0: whole rounds, up to max_batch ends a call.
  double batch_seconds = 0;
  std::size_t max_batch = std::size_t(1) << 18;
};

struct CertifiedMotionStats {
  std::size_t motions = 0;
  std::size_t checks = 0;  // configurations checked (with clearances and plain)
  std::size_t rounds = 0;
  std::size_t batches = 0;
};

// Calls from several threads at once are safe (each with its own segments; the checker
// takes concurrent calls; the statistics are added under a lock); set_stop and
// reset_stats are for the owner's thread, not while calls run.
class CertifiedMotions : public MotionChecker {
 public:
  // `scene` and `checker` must outlive this object.
  CertifiedMotions(const Scene& scene, CollisionChecker* checker,
                   const CertifiedMotionOptions& options = {});

  // from, to: shape [count, width]; invalid: shape [count], 0 when every configuration
  // on the motion (both ends included) is certified free, 1 otherwise. Returns false,
  // with `invalid` incomplete, when the stop condition said to stop between rounds.
  bool check_motions(const float* from, const float* to, std::size_t count,
                     std::uint8_t* invalid) override;

  void set_stop(std::function<bool()> should_stop) { should_stop_ = std::move(should_stop); }
  double step() const { return step_; }
  double finest_step() const { return finest_step_; }
  CertifiedMotionStats stats() const;
  void reset_stats();

 private:
  const Scene& scene_;
  CollisionChecker* checker_;
  MotionBound bound_;
  double step_ = 0, finest_step_ = 0;
  TimedBatchSize batch_size_;  // ends per checker call
  std::function<bool()> should_stop_;
  mutable std::mutex stats_mutex_;
  CertifiedMotionStats stats_;
};

}  // namespace gplanner
