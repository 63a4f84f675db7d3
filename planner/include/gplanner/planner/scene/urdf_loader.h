#pragma once
// Robots from URDF (through urdfdom) and SRDF files, with their collision meshes.

#include <map>
#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/robot_model.h"

namespace gplanner {

// ROS package name -> folder, so that package://NAME/rest names FOLDER/rest.
using PackageMap = std::map<std::string, std::string>;

// Resolves a URDF resource: package://NAME/path through `packages`, file:///abs/path,
// or a path relative to `base_folder`. Throws InputError for an unknown package or a
// malformed URI (such as package:/// with no package name).
std::string resolve_resource(const std::string& uri, const std::string& base_folder,
                             const PackageMap& packages, const SourceLocation& where);

// Loads a URDF: links in topological order, joints (revolute, continuous, prismatic,
// fixed, floating, planar; limits; mimic), collision geometry as triangle meshes in the
// link frame (meshes through assimp with the URDF scale, primitives tessellated).
// Adjacent links (adjacent_link_pairs) are disabled pairs. Throws InputError naming
// the URDF (and the element and line where known) or `referenced_from` when the file
// itself is missing; a <collision> that cannot be read whole (an origin, size or scale
// that is not finite numbers of the right count and sign, a missing or unknown shape)
// and a robot without any collision geometry are errors, as is a link whose collisions
// urdfdom drops for another element it cannot read. Elements a link or collision does
// not define, and COLLADA up axes ignored (see load_mesh), are reported in `notices`
// (when given), a line each.
RobotModel load_urdf(const std::string& urdf_path, const PackageMap& packages,
                     const SourceLocation& referenced_from,
                     std::vector<std::string>* notices = nullptr);

// Adds the SRDF's disable_collisions pairs. Elements outside what we use are skipped;
// elements outside the SRDF core are reported once each in `notices`. Pairs naming links
// the URDF lacks are skipped, as srdfdom skips them, with one notice listing them.
// Returns the number of disable_collisions elements applied.
int apply_srdf(RobotModel* robot, const std::string& srdf_path,
               const SourceLocation& referenced_from, std::vector<std::string>* notices);

// The joints of the SRDF's planning group `group` that take a value (revolute,
// continuous, prismatic, not mimic), in the robot's order (parents first), as MoveIt
// makes them from the group's <joint>, <link>, <chain> and nested <group> elements.
// Throws InputError naming the SRDF (or `referenced_from` when the group is missing)
// when the group does not exist or names what the URDF lacks.
std::vector<int> srdf_group_joints(const RobotModel& robot, const std::string& srdf_path,
                                   const std::string& group, const SourceLocation& referenced_from);

}  // namespace gplanner
