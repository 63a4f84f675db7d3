#include "gplanner/planner/planning/motion_bound.h"

#include <algorithm>
#include <cmath>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {

MotionBound::MotionBound(const RobotModel& robot, const ConfigurationSpace& space)
    : robot_(robot), space_(space), root_reach_(robot_reach(robot, space)) {
  const std::size_t links = robot.links.size();
  // subtree_reach[l]: how far any point of link l or the links below it can lie from
  // l's origin, whatever the joints below do. Children come after parents, so a
  // backward sweep sees every child first.
  std::vector<double> subtree_reach(links, 0.0);
  for (std::size_t l = links; l-- > 0;) {
    for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
      subtree_reach[l] = std::max(subtree_reach[l], p.norm());
  }
  for (std::size_t l = links; l-- > 1;) {
    const Joint& joint = robot.joints[robot.links[l].parent_joint];
    double travel = joint.X_PJ.translation().norm();
    if (joint.type == JointType::kPrismatic)
      travel += std::max(std::fabs(joint.lower), std::fabs(joint.upper));
    subtree_reach[joint.parent_link] =
        std::max(subtree_reach[joint.parent_link], travel + subtree_reach[l]);
  }
  // Motion per unit of a robot joint: a revolute joint swings its child's subtree about
  // its axis through the child's origin; a prismatic one translates it.
  std::vector<double>& per_unit = per_unit_;
  per_unit.assign(robot.joints.size(), 0.0);
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const Joint& joint = robot.joints[j];
    if (joint.type == JointType::kPrismatic) {
      per_unit[j] = 1.0;
    } else if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
      per_unit[j] = subtree_reach[joint.child_link];
    }
  }
  // A planned joint also drives the joints that mimic it.
  joint_reach_.assign(space.planned_joints.size(), 0.0);
  driver_.assign(robot.joints.size(), -1);
  driver_factor_.assign(robot.joints.size(), 0.0);
  for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
    const int master = space.planned_joints[i];
    joint_reach_[i] = per_unit[master];
    driver_[master] = static_cast<int>(i);
    driver_factor_[master] = 1.0;
    for (std::size_t j = 0; j < robot.joints.size(); ++j) {
      if (robot.joints[j].mimic_joint == master) {
        joint_reach_[i] += std::fabs(robot.joints[j].mimic_multiplier) * per_unit[j];
        driver_[j] = static_cast<int>(i);
        driver_factor_[j] = std::fabs(robot.joints[j].mimic_multiplier);
      }
    }
  }
}

double MotionBound::base_displacement(const float* a, const float* b) const {
  if (space_.base == BaseType::kFloating) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return std::sqrt(dx * dx + dy * dy + dz * dz) + quaternion_angle(a + 3, b + 3) * root_reach_;
  }
  if (space_.base == BaseType::kPlanar) {
    const double dx = a[0] - b[0], dy = a[1] - b[1];
    return std::sqrt(dx * dx + dy * dy) + angle_difference(a[2], b[2]) * root_reach_;
  }
  return 0;
}

double MotionBound::joint_change(const float* a, const float* b, std::size_t i) const {
  const float x = a[space_.base_width() + i], y = b[space_.base_width() + i];
  return space_.continuous[i] ? angle_difference(x, y) : std::fabs(x - y);
}

void MotionBound::link_displacements(const float* a, const float* b, double* out) const {
  const std::size_t links = robot_.links.size();
  if (links == 0) return;
  out[0] = base_displacement(a, b);
  // Parents come before their children.
  for (std::size_t l = 1; l < links; ++l) {
    const int j = robot_.links[l].parent_joint;
    const Joint& joint = robot_.joints[j];
    const double change = driver_[j] >= 0 ? driver_factor_[j] * joint_change(a, b, driver_[j]) : 0;
    out[l] = out[joint.parent_link] + change * per_unit_[j];
  }
}

double MotionBound::displacement(const float* a, const float* b) const {
  double motion = base_displacement(a, b);
  for (std::size_t i = 0; i < joint_reach_.size(); ++i)
    motion += joint_change(a, b, i) * joint_reach_[i];
  return motion;
}

double MotionBound::longest_displacement() const {
  constexpr double kPi = 3.14159265358979323846;
  double motion = 0;
  if (space_.base == BaseType::kFloating) {
    motion += (space_.base_max - space_.base_min).norm() + kPi * root_reach_;
  } else if (space_.base == BaseType::kPlanar) {
    motion += (space_.base_max - space_.base_min).head<2>().norm() + kPi * root_reach_;
  }
  for (std::size_t i = 0; i < joint_reach_.size(); ++i) {
    const double range = space_.continuous[i] ? kPi : space_.upper[i] - space_.lower[i];
    motion += range * joint_reach_[i];
  }
  return motion;
}

}  // namespace gplanner
