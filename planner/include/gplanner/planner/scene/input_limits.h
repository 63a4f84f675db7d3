#pragma once
// How large a scene's parts may be: limits that keep loading and planning feasible,
// each refused with an InputError naming the key or file and the limit.

#include <cstddef>

namespace gplanner {

inline constexpr std::size_t kMaxObstacles = 10000;           // obstacles: per scene
inline constexpr std::size_t kMaxMeshTriangles = 20000000;    // triangles of one mesh file
inline constexpr std::size_t kMaxSceneTriangles = 50000000;   // obstacle triangles in all
inline constexpr std::size_t kMaxRobotLinks = 1000;           // links of one URDF

// Most segments the longest motion of a space may be cut into (scenes asking for more,
// through edge_resolution or max_displacement, are refused at load): the final check,
// finer by planner.final_check_refinement, then takes up to 1e6 samples an edge.
inline constexpr double kMaxEdgeSegments = 1e5;

}  // namespace gplanner
