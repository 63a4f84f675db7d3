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

  // Per robot link l, a bound on how far any point of l moves along the motion (metres;
  // out: shape [robot links]): the base's motion, plus each joint's change between the
  // root and l times the reach of the links it carries. A link's bound adds to its
  // parent's, so out[a] - out[h] bounds how far a's points move relative to its ancestor
  // link h (CollisionChecker::check_clearances rests on this).
  void link_displacements(const float* a, const float* b, double* out) const;

  // The bound for the longest motion the space allows (the base across its bounds'
  // diagonal and through a half turn, every joint across its range, a continuous one
  // through a half turn): no edge moves a robot point farther. Metres.
  double longest_displacement() const;

  double root_reach() const { return root_reach_; }
  // Per planned joint: metres of point motion per unit of joint motion.
  const std::vector<double>& joint_reach() const { return joint_reach_; }

 private:
  // The base's part of displacement(), and the change of planned joint i.
  double base_displacement(const float* a, const float* b) const;
  double joint_change(const float* a, const float* b, std::size_t i) const;

  const RobotModel& robot_;
  const ConfigurationSpace& space_;
  double root_reach_ = 0;
  std::vector<double> joint_reach_;
  // Per robot joint: metres of point motion per unit of its value, and the planned
  // joint driving it (-1: none) with the factor of that drive (a mimic's multiplier).
  std::vector<double> per_unit_;
  std::vector<int> driver_;
  std::vector<double> driver_factor_;
};

}  // namespace gplanner
