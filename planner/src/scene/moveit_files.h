#pragma once
// MoveIt's files as parts of a scene (docs/scenes.md, "MoveIt files"): a planning scene
// (a moveit_msgs/PlanningScene as YAML, as MotionBenchMaker writes it, or MoveIt's .scene
// text, as RViz's Motion Planning panel exports it) gives obstacles,
// allowed collisions and joint values; a motion plan request (moveit_msgs/
// MotionPlanRequest as YAML) gives the planning group, the start and a joint goal.

#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

// A joint's value as a MoveIt file gives it, and where.
struct MoveItJointValue {
  std::string name;
  double value = 0;
  SourceLocation where;
};

struct MoveItRequest {
  std::string group;
  SourceLocation group_defined;
  std::vector<MoveItJointValue> start;  // start_state.joint_state
  std::vector<MoveItJointValue> goal;   // goal_constraints[0].joint_constraints
};

// Reads the planning scene at `path` (checked as an input file; MoveIt's .scene text where
// the name ends in .scene, a PlanningScene as YAML otherwise) into `scene` (its robot
// loaded): each collision object's primitives and meshes appended to scene->obstacles in
// the world frame, named by the object's id; its allowed collision matrix's allowed link
// pairs added to the robot's disabled pairs (pairs with a world object, and default
// entries, are left checked, with a notice: conservative). Returns robot_state's joint
// values (none from a .scene). Every problem is an InputError naming the file, its line
// and the key.
std::vector<MoveItJointValue> read_moveit_scene(const std::string& path, Scene* scene);

// Reads the motion plan request at `path`: one goal of joint constraints only (a pose
// or path constraint is refused: gplanner plans to joint goals), the group's name, the
// start state's joint values.
MoveItRequest read_moveit_request(const std::string& path);

}  // namespace gplanner
