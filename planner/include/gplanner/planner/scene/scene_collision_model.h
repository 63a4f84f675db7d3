#pragma once
// From a Scene to the flat CollisionModel of the collision core: kinematics as arrays,
// one BVH per link and for the environment, checked pairs, and the tolerance band.

#include "gplanner/collision_gpu/collision_model.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

// The tolerance band of a scene (docs/design.md, "The tolerance band"): delta is
// delta_fraction (at most 1e-5) of the scene's size, and never more than
// kRobotBandFraction of the robot's own size, so that it is small and finite in every
// scene (a fixed-base robot with no obstacle in reach, a large floor, generous bounds).
struct ToleranceBand {
  double delta = 0;       // metres
  double scene_size = 0;  // diagonal of the box of the obstacles and of everywhere the
                          // robot can reach, in the scene frame
  double robot_size = 0;  // diagonal of the box of the robot's geometry at the start
  double reach = 0;       // robot_reach: how far any robot point lies from its root
  bool capped = false;    // the robot's size set delta
};
constexpr double kRobotBandFraction = 1e-3;
ToleranceBand tolerance_band(const Scene& scene);
double tolerance_delta(const Scene& scene);

// How far from the scene frame's origin a coordinate may lie for a band of `delta`:
// where float rounds (2^-24 relative) to at most delta / 16, so that the leaf test's
// threshold, delta / 2, covers eight such roundings of poses and vertices.
double largest_representable_coordinate(double delta);

// Throws InputError when a magnitude of the scene is one that float (and so the cpu and
// gpu backends) cannot hold within its band: an obstacle or the robot too large, a
// revolute joint turned too far, or the robot or an obstacle too far from the scene
// frame's origin. robot_at and bounds_at: where the scene gives the robot and bounds.
void check_band_representable(const Scene& scene, const SourceLocation& robot_at,
                              const SourceLocation& bounds_at);

CollisionModel build_collision_model(const Scene& scene);

// Per triangle, whether it belongs to a solid (Link::solid, Obstacle::solid; when those
// are empty, whether its connected component is closed).
std::vector<std::uint8_t> link_solid_triangles(const Link& link);
std::vector<std::uint8_t> obstacle_solid_triangles(const Obstacle& obstacle);

// The connected components of a mesh for the containment step (solids.h): those of the
// triangles marked solid, each a solid, and those of the others, each a surface.
std::vector<BodyComponent> mesh_body_components(const TriangleMesh& mesh,
                                                const std::vector<std::uint8_t>& solid);

// The environment's components, obstacle by obstacle. exact_round_primitives: each solid
// sphere or cylinder as one point, its centre, holding nothing (the fcl backend, which
// checks them as FCL's shapes, solid already); otherwise as its tessellation. A box is
// always its tessellation, which is exact.
std::vector<BodyComponent> environment_components(const Scene& scene, bool exact_round_primitives);

// Tessellates every solid sphere and cylinder obstacle anew, so finely that its faces lie
// within a fifth of the tolerance band of the exact shape (which the fcl backend checks),
// within a budget of triangles (a sphere at most 256 segments, a cylinder 4096); where
// the budget is not enough, sets its allowance_m and adds a notice.
void refine_primitive_obstacles(Scene* scene);

// A bound on how far any point of the robot can be from its root link's origin, over
// all joint values within limits.
double robot_reach(const RobotModel& robot, const ConfigurationSpace& space);

// Removes obstacle geometry the robot cannot reach anywhere within the bounds (the region
// the base can reach, grown by the robot's reach): a surface's triangles whose boxes miss
// that region, and solid components whose boxes miss it, whole (a solid is never opened,
// and one containing the region is kept). Returns how many triangles were removed.
// Obstacles left with no triangles are removed too.
std::size_t drop_unreachable_obstacle_triangles(Scene* scene);

}  // namespace gplanner
