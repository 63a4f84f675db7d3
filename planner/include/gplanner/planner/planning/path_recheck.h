#pragma once
// The independent check of a returned path: FCL (double precision, the reference
// checker) at every waypoint and along every segment at a resolution finer than the
// planner's by `refinement` (its edge_resolution and, when set, its max_displacement
// divided by it). Used by the tests and by `gplan-bench`, which re-checks every path a
// planner returns.

#include <string>
#include <vector>

namespace gplanner {

struct Scene;

// Why `path` (shape [waypoints, width]) fails the re-check ("waypoint 3 collides",
// "segment 2 (waypoints 2 to 3) collides at 1/10 of the edge resolution", "the path has
// fewer than 2 waypoints", "waypoint 4 is no configuration"), or "" when it passes. When
// `from_start_to_goal`, the path must also begin at the scene's start and end at its
// goal (within 1e-5 per entry).
std::string path_recheck_problem(const Scene& scene, const std::vector<float>& path,
                                 double refinement, bool from_start_to_goal);

}  // namespace gplanner
