#pragma once
// A picture of a plan (SVG): the obstacles and the robot at waypoints along the path,
// projected onto the plane of the scene's two largest extents (the floor plan, for
// the shipped scenes: viewed from above), with the path of the robot's root drawn
// through them, start in green and goal in red.

#include <string>
#include <vector>

namespace gplanner {

struct Scene;

// path: shape [waypoints, width]. Written atomically.
void write_path_picture(const std::string& file, const Scene& scene,
                        const std::vector<float>& path);

}  // namespace gplanner
