#pragma once
// Roadmap files for the hostile-input catalogue: a valid one saved by save_roadmap for
// a scene of the case, then edited byte by byte (with the checksum made right again
// where the edit is meant to get past it).

#include <yaml-cpp/yaml.h>

#include <string>

namespace gplanner::hostile {

// The bytes of a roadmap file for `folder`/scene (scene: default scene.yaml) holding
// the start, the goal and two more vertices joined by three edges, with `edit` applied:
//   truncate: N        the last N bytes cut off (the checksum is then wrong)
//   magic: TEXT        the first bytes overwritten by TEXT (no fix)
//   flip: OFFSET       the byte at OFFSET inverted (no fix: a checksum mismatch)
//   fingerprint, width, vertex_count, edge_count, vertex_value, edge_length, edge_a,
//   edge_b, edge_state: VALUE   that field (the first vertex's first value, the first
//                      edge's) set to VALUE, the checksum fixed
//   grow: N            N zero bytes added before the checksum, the checksum fixed
std::string roadmap_file(const std::string& folder, const YAML::Node& spec);

}  // namespace gplanner::hostile
