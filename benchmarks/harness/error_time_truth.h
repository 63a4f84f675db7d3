#pragma once
// The ground truth of the error-against-time study: FCL in double precision
// (FclChecker, on all cores).
// - A state: colliding or free, as FCL's collision check says.
// - A motion (an edge, a path's segment): free when FCL certifies it free at the fine
//   step (CertifiedMotions with the FclChecker: every configuration on it, ends
//   included, keeps the clearance its segment's bound asks for); colliding when one of
//   its ends or an FCL sample at that step (no robot point moving farther than the step
//   between samples) collides; undecided otherwise (neither proof: a motion that grazes
//   an obstacle closer than the certification can resolve, or that the certification
//   cannot handle; counted and reported, never counted as an error).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"

namespace gplan {

enum class MotionTruth : std::uint8_t { kFree, kColliding, kUndecided };

class GroundTruth {
 public:
  // step_m: the fine step in metres (> 0). `scene` must outlive this object.
  GroundTruth(const gplanner::Scene& scene, double step_m);

  // configurations: shape [n, width]; returns shape [n], 1 colliding, 0 free.
  std::vector<std::uint8_t> states(const float* configurations, std::size_t n);

  // from, to: shape [n, width]. Empty when `stop` said to stop.
  std::vector<MotionTruth> motions(const float* from, const float* to, std::size_t n,
                                   const std::function<bool()>& stop = {});

  // A path (shape [waypoints, width]): "pass" when every segment is certified free,
  // "fail" when some segment (or waypoint) collides, "undecided" otherwise; "" when
  // stopped.
  std::string path(const std::vector<float>& path, const std::function<bool()>& stop = {});

  double step() const { return step_; }
  gplanner::FclChecker* checker() { return &fcl_; }

 private:
  const gplanner::Scene& scene_;
  double step_;
  gplanner::FclChecker fcl_;
  gplanner::CertifiedMotions certified_;
  gplanner::LocalPlanner sampled_;
};

}  // namespace gplan
