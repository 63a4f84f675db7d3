#include "gplanner/planner/scene/forward_kinematics.h"

namespace gplanner {

Eigen::Isometry3d joint_transform(const Joint& joint, double position) {
  Eigen::Isometry3d X_JC = Eigen::Isometry3d::Identity();
  if (joint.type == JointType::kRevolute || joint.type == JointType::kContinuous) {
    X_JC.linear() = Eigen::AngleAxisd(position, joint.axis_J).toRotationMatrix();
  } else if (joint.type == JointType::kPrismatic) {
    X_JC.translation() = joint.axis_J * position;
  }
  return joint.X_PJ * X_JC;
}

void forward_kinematics(const RobotModel& robot, const Eigen::Isometry3d& X_WR,
                        const double* positions, std::vector<Eigen::Isometry3d>* X_WL) {
  X_WL->resize(robot.links.size());
  (*X_WL)[0] = X_WR;
  // Links are in topological order, so every parent pose is ready before its children.
  for (std::size_t l = 1; l < robot.links.size(); ++l) {
    const Joint& joint = robot.joints[robot.links[l].parent_joint];
    (*X_WL)[l] =
        (*X_WL)[joint.parent_link] * joint_transform(joint, positions[robot.links[l].parent_joint]);
  }
}

}  // namespace gplanner
