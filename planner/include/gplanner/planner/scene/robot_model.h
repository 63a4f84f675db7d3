#pragma once
// A robot as a kinematic tree of links carrying collision meshes, in topological order
// (every link after its parent), with the link pairs that self-collision ignores.

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

enum class JointType { kFixed, kRevolute, kContinuous, kPrismatic, kFloating, kPlanar };

const char* joint_type_name(JointType type);

struct Joint {
  std::string name;
  JointType type = JointType::kFixed;
  int parent_link = -1;
  int child_link = -1;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  // joint frame in parent link
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitX();       // unit axis in the joint frame
  // Position limits (radians or metres). Continuous joints: [-pi, pi], wrapping.
  double lower = 0;
  double upper = 0;
  // Mimic joints follow `mimic_joint`: q = multiplier * q_master + offset.
  int mimic_joint = -1;
  double mimic_multiplier = 1;
  double mimic_offset = 0;

  // One position value (revolute, continuous, prismatic); others have none here
  // (floating and planar joints inside a URDF are driven by the base, not as joints).
  bool is_single_dof() const {
    return type == JointType::kRevolute || type == JointType::kContinuous ||
           type == JointType::kPrismatic;
  }
};

struct Link {
  std::string name;
  int parent_joint = -1;   // -1 for the root link
  TriangleMesh collision;  // in the link frame; empty when the link has no collision geometry
  // Per triangle of collision: 1 where it belongs to a closed connected component of
  // its collision element (a solid), 0 where it is a surface. Empty: decided from
  // collision alone (closed_triangles).
  std::vector<std::uint8_t> solid;
};

struct RobotModel {
  std::string name;
  std::string source_file;  // the URDF (or mesh) it came from
  std::vector<Link> links;  // links[0] is the root; parents before children
  std::vector<Joint> joints;
  // Link pairs (lower index first) never checked against each other: adjacent links
  // (adjacent_link_pairs) and the SRDF's disable_collisions.
  std::vector<std::pair<int, int>> disabled_pairs;
  std::string srdf_file;
  // The files its collision geometry was loaded from: a URDF's <mesh> files and what
  // they reference (an OBJ's .mtl).
  std::vector<std::string> mesh_files;

  int find_link(const std::string& name) const;   // -1 when absent
  int find_joint(const std::string& name) const;  // -1 when absent
  std::size_t triangle_count() const;

  // Pairs of links that both carry collision geometry and are neither adjacent nor
  // disabled: the self-collision workload.
  std::vector<std::pair<int, int>> checked_pairs() const;
  // The deepest link that links a and b both are or hang from.
  int deepest_common_link(int a, int b) const;
};

// Adjacent links, as MoveIt's Setup Assistant finds them (compute_default_collisions):
// every parent and child joined by a joint, and every two links with collision geometry
// joined through a chain of links without any (a geometry-less link joins its parent and
// its children, so also two children of a geometry-less parent). Sorted, lower index
// first.
std::vector<std::pair<int, int>> adjacent_link_pairs(const RobotModel& robot);

// A rigid body robot: one link holding `mesh`, driven by a floating base.
RobotModel make_rigid_robot(const std::string& name, TriangleMesh mesh,
                            const std::string& source_file);

}  // namespace gplanner
