#pragma once
// A planning problem: the robot, how configurations map onto it, the static obstacles,
// start and goal, and planner settings; all of it in the scene frame S (see p_WS).

#include <cstdint>
#include <string>
#include <vector>

#include "gplanner/planner/scene/configuration_space.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/planner_settings.h"
#include "gplanner/planner/scene/robot_model.h"
#include "gplanner/planner/scene/triangle_mesh.h"

namespace gplanner {

enum class ObstacleShape { kMesh, kBox, kSphere, kCylinder };

struct Obstacle {
  std::string name;
  TriangleMesh mesh_S;  // in the scene frame; a primitive's tessellation, which contains it
  // Per triangle of mesh_S: 1 where it belongs to a solid (a closed connected component
  // of an obstacle not marked `solid: false`), 0 where it is a surface; decided at load
  // (docs/scenes.md, "Solids"). Empty: decided from mesh_S alone (closed_triangles).
  std::vector<std::uint8_t> solid;
  // Primitives: the exact shape and its pose, which the fcl backend checks as an FCL
  // primitive when solid. dimensions: a box's side lengths, a sphere's (radius, 0, 0), a
  // cylinder's (radius, length, 0) (axis z, centred).
  ObstacleShape shape = ObstacleShape::kMesh;
  Eigen::Vector3d dimensions = Eigen::Vector3d::Zero();
  Eigen::Isometry3d X_SO = Eigen::Isometry3d::Identity();
  // How far a solid sphere's or cylinder's tessellation lies outside the exact shape
  // where that is more than the band allows (its triangle budget reached); 0 otherwise.
  // `gplan check --compare` counts collisions reported within it of the shape as within
  // the band (docs/design.md, "Solids").
  double allowance_m = 0;
  std::string file;        // a mesh obstacle's file
  SourceLocation defined;  // where the scene defines it

  // A solid box, sphere or cylinder.
  bool is_solid_primitive() const;
  // A solid sphere or cylinder: checked as FCL's own shape by the fcl backend. A solid
  // box is checked there as its 12 triangles, which are exact (FCL's GJK misses some
  // box-triangle intersections; docs/design.md, "Solids").
  bool is_solid_round_primitive() const;
};

struct Scene {
  // The scene frame S is the world frame translated to p_WS. Everything geometric here
  // (obstacles, bounds, the base frame of a fixed or planar base, start, goal and so
  // every configuration row) is in S, made relative to it in double at load, before
  // anything is rounded to float: far from the world origin a float cannot place a
  // pose within the tolerance band (its spacing at 1e5 m is 7.8 mm). p_WS is zero,
  // and S the world, for a scene near the origin (see scene_frame_origin).
  Eigen::Vector3d p_WS = Eigen::Vector3d::Zero();
  std::string file;  // the scene file as given
  std::string name;
  std::string description;
  std::string narrowest_passage;
  RobotModel robot;
  ConfigurationSpace space;
  std::vector<Obstacle> obstacles;
  // Obstacle triangles dropped at load because the robot cannot reach them (open
  // components triangle by triangle, closed ones whole).
  std::size_t dropped_obstacle_triangles = 0;
  std::vector<float> start;  // shape: [space.width()]
  std::vector<float> goal;   // shape: [space.width()]
  SourceLocation start_defined;
  SourceLocation goal_defined;
  PlannerSettings planner;
  // Things skipped or changed while loading (the scene frame, when moved), a line each.
  std::vector<std::string> notices;
  // Every file read to build the scene (the scene file, URDF, SRDF, each mesh), as
  // named; outputs must not be any of them (check_output_paths).
  std::vector<std::string> input_files;

  Eigen::Isometry3d X_WS() const;
  std::size_t obstacle_triangle_count() const;
  // All obstacles as one mesh in the scene frame: the static environment every
  // checker builds its BVH over.
  TriangleMesh environment_mesh() const;
  // Bounds of everything the scene holds, in the scene frame: obstacles and the region
  // a moving base's root can be in.
  Eigen::AlignedBox3d bounds_S() const;
};

// The rule for p_WS, given the bounds of everything a scene holds in the world
// (obstacles and where the root can be, fixed or not), centre c and diagonal d: the
// world origin while |c| <= d, so that every scene near the origin (all shipped ones)
// keeps its rows, roadmaps and results; beyond, c rounded to a multiple of the largest
// power of ten not above d, so that rows stay short and readable. Either way
// coordinates in S stay below about 1.5 d, where float rounding (2^-24 relative) is
// under 1% of the default band (1e-5 d).
Eigen::Vector3d scene_frame_origin(const Eigen::AlignedBox3d& bounds_W);

// Reads and validates a scene file, loading its robot and obstacle meshes and dropping
// obstacle triangles out of the robot's reach. Throws
// InputError naming the file, line and key, and what to change. Start and goal are
// checked against bounds and limits here; whether they collide needs a checker (see
// check_start_and_goal in collision_checker.h).
Scene load_scene(const std::string& path);

}  // namespace gplanner
