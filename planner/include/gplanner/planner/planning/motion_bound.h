#pragma once
// A bound on how far any point of the robot moves along the straight-line motion
// between two configurations: base translation, plus base rotation angle times the
// robot's reach from its root, plus each joint's change times the reach of the links it
// carries (a prismatic joint moves them by its change). Used to sample edges so that no
// robot point moves more than a given distance between samples.

#include <vector>

#include "gplanner/planner/scene/configuration_space.h"
#include "gplanner/planner/scene/robot_model.h"

namespace gplanner {

class MotionBound {
 public:
  MotionBound(const RobotModel& robot, const ConfigurationSpace& space);

  // Metres; a and b: shape [space.width()].
  double displacement(const float* a, const float* b) const;

  // The bound for the longest motion the space allows (the base across its bounds'
  // diagonal and through a half turn, every joint across its range, a continuous one
  // through a half turn): no edge moves a robot point farther. Metres.
  double longest_displacement() const;

  double root_reach() const { return root_reach_; }
  // Per planned joint: metres of point motion per unit of joint motion.
  const std::vector<double>& joint_reach() const { return joint_reach_; }

 private:
  const ConfigurationSpace& space_;
  double root_reach_ = 0;
  std::vector<double> joint_reach_;
};

}  // namespace gplanner
