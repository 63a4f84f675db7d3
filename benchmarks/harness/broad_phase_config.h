#pragma once
// The keys of a `gplan-bench` configuration of kind broad-phase (the sphere broad-phase
// study, benchmarks/harness/broad_phase_study.h): which methods, at which sphere counts, for how
// many frames, and the spheres' sizes and motion. See benchmarks/README.md, "Broad phase".

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace YAML {
class Node;
}
namespace gplanner {
class YamlReader;
}

namespace gplan {

struct BroadPhaseOptions {
  // cpu-all-pairs, cpu-sort-sweep, gpu-all-pairs, gpu-sort-sweep, gpu-grid, gpu-lbvh (at
  // least one).
  std::vector<std::string> methods;
  // Sphere counts, each a point of every method (ascending in the tables).
  std::vector<std::uint64_t> counts;
  // The largest count a method runs at (absent: no cap): the O(n^2) methods' time grows
  // with the square of the count.
  std::map<std::string, std::uint64_t> max_count;
  int frames = 200;           // timed frames per count (the seed's 200 readings) ...
  int min_frames = 3;         // ... at least this many ...
  double count_budget_s = 5;  // ... and no new frame once the count has spent this long
  double radius_min = 0.5;    // radii uniform in [radius_min, radius_max]
  double radius_max = 0.5;
  // The spheres' volume over the box's: the box grows with the count, so that the pairs
  // per sphere stay about the same.
  double volume_fraction = 0.05;
  double speed = 0.05;  // the largest distance a sphere moves in a frame, in mean radii
};

// The broad-phase keys (besides name, kind, seed) and their reader.
const std::vector<std::string>& broad_phase_keys();

// Reads the broad-phase keys of `root`; throws gplanner::InputError naming the file, line
// and key, what is wrong and what to change.
BroadPhaseOptions read_broad_phase_options(const gplanner::YamlReader& in, const YAML::Node& root);

}  // namespace gplan
