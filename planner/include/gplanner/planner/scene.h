#pragma once
// A planning problem: the robot, how configurations map onto it, the static obstacles
// in the world frame, start and goal, and planner settings.

#include <string>
#include <vector>

#include "gplanner/planner/configuration_space.h"
#include "gplanner/planner/input_error.h"
#include "gplanner/planner/planner_settings.h"
#include "gplanner/planner/robot_model.h"
#include "gplanner/planner/triangle_mesh.h"

namespace gplanner {

struct Obstacle {
  std::string name;
  TriangleMesh mesh_W;     // in the world frame
  SourceLocation defined;  // where the scene defines it
};

struct Scene {
  std::string file;  // the scene file as given
  std::string name;
  std::string description;
  std::string narrowest_passage;
  RobotModel robot;
  ConfigurationSpace space;
  std::vector<Obstacle> obstacles;
  // Obstacle triangles dropped at load because the robot cannot reach them.
  std::size_t dropped_obstacle_triangles = 0;
  std::vector<float> start;  // shape: [space.width()]
  std::vector<float> goal;   // shape: [space.width()]
  SourceLocation start_defined;
  SourceLocation goal_defined;
  PlannerSettings planner;
  std::vector<std::string> notices;  // things skipped while loading, worth a line each

  std::size_t obstacle_triangle_count() const;
  // All obstacles as one mesh in the world frame: the static environment every
  // checker builds its BVH over.
  TriangleMesh environment_mesh() const;
  // Bounds of everything the scene holds: obstacles and the base bounds.
  Eigen::AlignedBox3d world_bounds() const;
};

// Reads and validates a scene file, loading its robot and obstacle meshes and dropping
// obstacle triangles out of the robot's reach. Throws
// InputError naming the file, line and key, and what to change. Start and goal are
// checked against bounds and limits here; whether they collide needs a checker (see
// check_start_and_goal in collision_checker.h).
Scene load_scene(const std::string& path);

}  // namespace gplanner
