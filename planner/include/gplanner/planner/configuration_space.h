#pragma once
// How a row of floats maps onto a robot: the base pose first (floating: x y z qw qx qy
// qz; planar: x y theta; fixed: nothing), then the planned joints in scene order.

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "gplanner/planner/robot_model.h"

namespace gplanner {

enum class BaseType { kFixed, kPlanar, kFloating };

const char* base_type_name(BaseType type);

struct ConfigurationSpace {
  BaseType base = BaseType::kFixed;
  // Fixed base: the robot root in the world. Planar base: the frame of the plane in
  // which x, y, theta move the root.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  // Base position bounds: x y z (floating) or x y (planar; z unused).
  Eigen::Vector3d base_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d base_max = Eigen::Vector3d::Zero();
  std::vector<int> planned_joints;      // robot joint indices, in configuration order
  std::vector<double> lower, upper;     // per planned joint
  std::vector<bool> continuous;         // per planned joint: wraps at +-pi
  std::vector<double> fixed_positions;  // per robot joint: its value when not planned

  int base_width() const;  // floats of the base pose: 0, 3 or 7
  int width() const;       // floats per configuration
  int dof() const;         // degrees of freedom (a quaternion counts 3)

  // X_WR: the robot's root link in the world for configuration q (shape: [width]).
  Eigen::Isometry3d base_pose(const float* q) const;

  // Position of every robot joint (shape: [robot.joints.size()]): planned joints from q,
  // the others at their fixed value, mimic joints following their masters.
  void joint_positions(const RobotModel& robot, const float* q, double* positions) const;

  // A uniform random configuration within bounds and limits (rotations uniform on
  // SO(3)), written to q (shape: [width]).
  void sample_uniform(std::mt19937_64* rng, float* q) const;

  // The point a fraction t in [0, 1] of the way from a to b: positions and joints
  // linearly, the floating rotation by slerp the short way, continuous joints and the
  // planar angle the short way round.
  void interpolate(const float* a, const float* b, double t, float* out) const;

  // Empty when q lies within bounds and limits (quaternion of unit length within
  // 1e-3), otherwise what is out of range, naming `names` entries.
  std::string out_of_bounds(const RobotModel& robot, const float* q) const;

  // Name of configuration entry i ("x", "qw", "theta", a joint name).
  std::string entry_name(const RobotModel& robot, int i) const;
};

// Wraps an angle into [-pi, pi).
double wrap_angle(double angle);

}  // namespace gplanner
