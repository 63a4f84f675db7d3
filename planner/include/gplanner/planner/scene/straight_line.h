#pragma once
// The straight motion between two configurations, prepared for sampling many points of
// it: at(t, out) writes exactly the floats ConfigurationSpace::interpolate(a, b, t, out)
// writes (the same operations in double, in the same order), with what depends only on
// a and b (the differences, the short way round of angles, the normalised rotations)
// worked out once by reset(). Where one motion gives many samples (a local planner's
// levels, a tree's rows), the entries then go in one loop the compiler vectorises:
// pr2_reach's 15 entries a sample in a third of interpolate's time (build host).

#include <Eigen/Geometry>
#include <vector>

#include "gplanner/planner/scene/configuration_space.h"

namespace gplanner {

class StraightLine {
 public:
  // The motion from a to b (shape: [space.width()]). A line may be reset for another
  // motion, keeping its memory (one a thread).
  void reset(const ConfigurationSpace& space, const float* a, const float* b);
  // The point a fraction t of the way (shape: [width]), as interpolate gives it.
  void at(double t, float* out) const;

 private:
  std::vector<double> from_, delta_;  // per entry: a, and b - a (the short way for angles)
  std::vector<int> wrapped_;          // entries wrapped into [-pi, pi)
  bool floating_ = false;             // entries 3 to 6: qa_ to qb_ by slerp
  Eigen::Quaterniond qa_, qb_;        // normalised
};

}  // namespace gplanner
