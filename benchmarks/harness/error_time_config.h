#pragma once
// The keys of a `gplan-bench` configuration of kind error-time (the error-against-time
// study, benchmarks/harness/error_time_study.h): what the study sweeps and how large its ground
// truth is. See benchmarks/README.md, "Error against time".

#include <cstdint>
#include <string>
#include <vector>

namespace YAML {
class Node;
}
namespace gplanner {
class YamlReader;
}

namespace gplan {

struct ErrorTimeOptions {
  // Which curves run: gpu (traversal, precision, delta, edges and planning on the gpu
  // backend), cpu, fcl. At least one.
  std::vector<std::string> checkers;
  // The planning curves' checkers, among `checkers` (default: all of them; planning on
  // FCL is slow on articulated robots).
  std::vector<std::string> plan_checkers;
  std::uint64_t states = 10000;  // N seeded random states
  std::uint64_t edges = 1000;    // M seeded roadmap-like edges
  // Free milestones of the roadmap the edges are taken from (0: the scene's
  // planner.roadmap.milestones), each joined to the scene's planner.roadmap.neighbors.
  std::uint64_t roadmap_milestones = 0;
  // Sampled edges: the scene's edge resolution (its max_displacement where set) times
  // each of these (4: four times coarser; 0.125: eight times finer).
  std::vector<double> edge_resolutions = {4, 2, 1, 0.5, 0.25, 0.125};
  // Certified edges: first step (MotionBound metres) as fractions of the longest motion
  // the scene's space allows.
  std::vector<double> certified_steps = {0.004, 0.002, 0.001};
  // The ground truth's first step, the same kind of fraction, at most the smallest of
  // certified_steps (it refines near obstacles down to 1/1024 of it).
  double truth_step = 0.001;
  // The tolerance band (planner.delta_fraction), each value in (0, 1e-5].
  std::vector<double> deltas = {1e-5, 3e-6, 1e-6};
  // Planning: first-round milestones of ours-lazyprm, each a point of the milestones
  // curve; the edge-checks curve plans at the scene's own count.
  std::vector<double> plan_milestones = {500, 1000, 2000, 4000};
  int runs = 5;              // planning runs per point (seeds seed, seed + 1, ...)
  double time_limit_s = 30;  // per planning run
  int repeat = 3;            // timed calls per state or edge point (the median is kept)
};

// The error-time keys (besides name, kind, scenes, seed) and their readers.
const std::vector<std::string>& error_time_keys();

// Reads the error-time keys of `root`; throws gplanner::InputError naming the file, line
// and key, what is wrong and what to change.
ErrorTimeOptions read_error_time_options(const gplanner::YamlReader& in, const YAML::Node& root);

}  // namespace gplan
