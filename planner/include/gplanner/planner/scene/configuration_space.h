#pragma once
// How a row of floats maps onto a robot: the base pose first (floating: x y z qw qx qy
// qz; planar: x y theta; fixed: nothing), then the planned joints in scene order.
// Rows are in the scene frame S (see Scene::p_WS): a row's base position is measured
// from row_origin, so that it stays small (and exact enough in float) however far the
// scene lies from the world origin.

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

#include "gplanner/planner/scene/robot_model.h"

namespace gplanner {

enum class BaseType { kFixed, kPlanar, kFloating };

const char* base_type_name(BaseType type);

struct ConfigurationSpace {
  BaseType base = BaseType::kFixed;
  // Fixed base: the robot root in the scene frame. Planar base: the frame of the plane
  // in which x, y, theta move the root, its origin at row_origin of the plane.
  Eigen::Isometry3d X_SB = Eigen::Isometry3d::Identity();
  // Base position bounds of rows: x y z (floating) or x y (planar; z unused).
  Eigen::Vector3d base_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d base_max = Eigen::Vector3d::Zero();
  // Where a row's base position is measured from, in the coordinates the scene file
  // uses for it (the world for a floating base, the plane for a planar one): a row's x
  // is the file's x minus row_origin.x(). Zero unless the scene lies far from the world
  // origin.
  Eigen::Vector3d row_origin = Eigen::Vector3d::Zero();
  std::vector<int> planned_joints;      // robot joint indices, in configuration order
  std::vector<double> lower, upper;     // per planned joint
  std::vector<bool> continuous;         // per planned joint: wraps at +-pi
  std::vector<double> fixed_positions;  // per robot joint: its value when not planned

  int base_width() const;      // floats of the base pose: 0, 3 or 7
  int position_width() const;  // of which the base position: 0, 2 or 3
  int width() const;           // floats per configuration
  int dof() const;             // degrees of freedom (a quaternion counts 3)

  // X_SR: the robot's root link in the scene frame for configuration q (shape: [width]).
  Eigen::Isometry3d base_pose(const float* q) const;

  // The box the root's origin can lie in, in the scene frame: the bounds (mapped
  // through the plane for a planar base), or the fixed root's position.
  Eigen::AlignedBox3d base_region() const;

  // A row (shape: [width]) as the scene file writes it, in double: the base position
  // plus row_origin, the other entries as they are; and back, rounding to float only
  // after the base position is made relative to row_origin.
  void to_file_values(const float* q, double* values) const;
  void from_file_values(const double* values, float* q) const;

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
  // 1e-3), otherwise what is out of range, naming `names` entries; positions are given
  // as the scene file gives them (plus row_origin). The double form takes the scene
  // file's values (to_file_values), so it judges far scenes before any rounding.
  std::string out_of_bounds(const RobotModel& robot, const float* q) const;
  std::string out_of_bounds_in_file_values(const RobotModel& robot, const double* values) const;

  // Name of configuration entry i ("x", "qw", "theta", a joint name).
  std::string entry_name(const RobotModel& robot, int i) const;

 private:
  // out_of_bounds of a row held in double.
  std::string out_of_bounds_in_row(const RobotModel& robot, const double* q) const;
};

// Wraps an angle into [-pi, pi).
double wrap_angle(double angle);

}  // namespace gplanner
