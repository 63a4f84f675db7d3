#pragma once
// The path file `gplan plan --out` writes (YAML): the plan's summary, the names of a
// configuration row's entries, and per waypoint its configuration (its base position as
// the scene file gives positions, not relative to the scene frame), the robot root's
// pose in the world and the value of every single-value joint by name.

#include <string>
#include <vector>

#include "gplanner/planner/planning/plan_result.h"  // PlanResult

namespace gplanner {

struct Scene;

// Written atomically: a failed write leaves `path` as it was.
void write_path_file(const std::string& path, const Scene& scene, const PlanResult& result,
                     const std::string& planner, const std::string& backend);

// The scene a path file names (its `scene:` key, as written: relative to where gplan ran).
// Throws InputError (file, line, key) where the file is not a path file.
std::string path_file_scene(const std::string& file);

// The waypoints of a path file (shape [waypoints, width]) as rows of `scene`: its
// `entries` must be the scene's configuration entries, and every waypoint's
// configuration one value per entry (at least 2 waypoints). Throws InputError (file,
// line, key) otherwise.
std::vector<float> read_path_file(const std::string& file, const Scene& scene);

}  // namespace gplanner
