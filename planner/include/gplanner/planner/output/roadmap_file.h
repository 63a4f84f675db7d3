#pragma once
// A roadmap's file (--save-roadmap, --load-roadmap): binary, naming the scene it was
// built for (a fingerprint of everything an edge's validity depends on), with a
// checksum.

#include <cstdint>
#include <string>

#include "gplanner/planner/planning/roadmap.h"

namespace gplanner {

struct Scene;

// 64-bit fingerprint of what decides a roadmap's validity in `scene`: the robot's
// geometry and kinematics, the obstacles, the configuration space (with the scene
// frame, where moved), the metric weights, the tolerance band and the edge resolution
// settings.
std::uint64_t scene_fingerprint(const Scene& scene);

// Writes the roadmap (atomically: a failed write leaves `path` as it was).
void save_roadmap(const Roadmap& roadmap, const Scene& scene, const std::string& path);

// Reads a roadmap saved for `scene`. Throws InputError naming the file (and the
// milestone or edge at fault) when it is not a regular file within kRoadmapFile's limit
// (input_file.h), not a roadmap, of a size its header's counts do not give (checked
// before it is read whole), damaged (checksum), for another scene, or holds a milestone
// that is not finite or lies outside the bounds and joint limits, or an edge whose
// length is not finite and 0 or more, that names a missing milestone or repeats another.
Roadmap load_roadmap(const Scene& scene, const std::string& path);

}  // namespace gplanner
