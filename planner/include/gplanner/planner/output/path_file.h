#pragma once
// The path file `gplan plan --out` writes (YAML): the plan's summary, the names of a
// configuration row's entries, and per waypoint its configuration (its base position as
// the scene file gives positions, not relative to the scene frame), the robot root's
// pose in the world and the value of every single-value joint by name.

#include <string>

#include "gplanner/planner/planning/plan_result.h"  // PlanResult

namespace gplanner {

struct Scene;

// Written atomically: a failed write leaves `path` as it was.
void write_path_file(const std::string& path, const Scene& scene, const PlanResult& result,
                     const std::string& planner, const std::string& backend);

}  // namespace gplanner
