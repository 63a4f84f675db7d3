#pragma once
// Link poses in the world from a base pose and joint positions (double precision: the
// reference that float32 kinematics elsewhere is measured against).

#include <Eigen/Geometry>
#include <vector>

#include "gplanner/planner/scene/robot_model.h"

namespace gplanner {

// X_PC of one joint at `position`: the child link in the parent link's frame. Floating
// and planar joints inside a URDF stay at their zero pose (the scene's base moves the
// root instead).
Eigen::Isometry3d joint_transform(const Joint& joint, double position);

// X_WL for every link (shape: [robot.links.size()]), from the root pose X_WR and the
// position of every joint (shape: [robot.joints.size()]).
void forward_kinematics(const RobotModel& robot, const Eigen::Isometry3d& X_WR,
                        const double* positions, std::vector<Eigen::Isometry3d>* X_WL);

}  // namespace gplanner
