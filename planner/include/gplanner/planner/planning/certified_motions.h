#pragma once
// Motions certified free: an answer that holds for every configuration on the straight
// motion, not only at samples.
//
// MotionBound bounds how far any robot point moves along a motion. Cut a motion into
// segments along which no point moves farther than d: a configuration inside a segment
// is within d/2 of one of the segment's two ends (every point of the robot), so if both
// ends keep a clearance of d/2 to the environment (and d between checked link pairs,
// whose points may approach each other by twice as much), the whole segment is free.
// Each round checks the ends of every open segment with that clearance
// (CollisionChecker::check_inflated, one batch per round); an end that fails it but is
// free itself (check()) splits its segment in two for the next round, at half the
// clearance, so that segments near obstacles are refined and those far from them are
// not; an end that collides makes the motion invalid. A segment still not certified
// when its bound has shrunk below `finest_step` makes the motion invalid too: certified
// answers are conservative. With the tolerance band of the checker (a configuration
// within delta of contact may be reported colliding), "certified free" means: no
// configuration on the motion brings any checked pair closer than 0 (FCL's distance).
//
// Not yet used by the planners (issue 21): the bound is the whole robot's, so a link pair
// checked for self-collision is held to the clearance of the largest motion of any robot
// point. Pairs that stay millimetres apart in every configuration (a gripper and its
// wrist) then never certify, and articulated robots' motions are all refused; per-pair
// bounds (the joints between the two links only) are the next step. For rigid robots
// (no link pairs) the clearance is half the segment's bound, and it certifies motions
// with millimetres to spare (tests/planner/planning/certified_motions_test.cpp).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/motion_bound.h"

namespace gplanner {

struct Scene;

struct CertifiedMotionOptions {
  // Metres: the first segments of a motion move no robot point farther than this. <= 0:
  // 1 % of the longest motion the space allows (MotionBound::longest_displacement).
  double step = 0;
  // Metres: a segment not certified when its bound is below this makes its motion
  // invalid. <= 0: step / 1024.
  double finest_step = 0;
};

struct CertifiedMotionStats {
  std::size_t motions = 0;
  std::size_t checks = 0;  // configurations checked (inflated and plain)
  std::size_t rounds = 0;
  std::size_t batches = 0;
};

class CertifiedMotions {
 public:
  // `scene` and `checker` must outlive this object.
  CertifiedMotions(const Scene& scene, CollisionChecker* checker,
                   const CertifiedMotionOptions& options = {});

  // from, to: shape [count, width]; invalid: shape [count], 0 when every configuration
  // on the motion (both ends included) is certified free, 1 otherwise. Returns false,
  // with `invalid` incomplete, when the stop condition said to stop between rounds.
  bool check_motions(const float* from, const float* to, std::size_t count, std::uint8_t* invalid);

  void set_stop(std::function<bool()> should_stop) { should_stop_ = std::move(should_stop); }
  double step() const { return step_; }
  double finest_step() const { return finest_step_; }
  // The clearance a segment end is checked with when its segment moves points up to `d`.
  double clearance(double d) const { return self_pairs_ ? d : d / 2; }
  CertifiedMotionStats stats() const;

 private:
  const Scene& scene_;
  CollisionChecker* checker_;
  MotionBound bound_;
  double step_ = 0, finest_step_ = 0;
  bool self_pairs_ = false;
  std::function<bool()> should_stop_;
  mutable std::mutex stats_mutex_;
  CertifiedMotionStats stats_;
};

}  // namespace gplanner
