#pragma once
// From a Scene to the flat CollisionModel of the collision core: kinematics as arrays,
// one BVH per link and for the environment, checked pairs, and the tolerance band.

#include "gplanner/collision_gpu/collision_model.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

// The tolerance band delta of a scene, in metres: delta_fraction times the diagonal of
// its bounds (see DESIGN.md).
double tolerance_delta(const Scene& scene);

CollisionModel build_collision_model(const Scene& scene);

// A bound on how far any point of the robot can be from its root link's origin, over
// all joint values within limits.
double robot_reach(const RobotModel& robot, const ConfigurationSpace& space);

// Removes obstacle triangles the robot cannot reach anywhere within the bounds (their
// boxes miss the region the base can reach, grown by the robot's reach); returns how
// many were removed. Obstacles left with no triangles are removed too.
std::size_t drop_unreachable_obstacle_triangles(Scene* scene);

}  // namespace gplanner
