#pragma once
// The seed's query tables as `gplan-bench` measures them (Pan & Manocha, "Timing
// Results" and "Applications to PR2 Model"): timed batch calls of one checker on one
// scene, a BenchRecord per call.
// - "collision-queries" (the seed's milestone computation): a batch of configurations
//   drawn uniformly within the scene's bounds and joint limits from the seed, as
//   `gplan check` draws them, checked in one call.
// - "local-planning": a roadmap's edges checked as the planner checks them
//   (LocalPlanner::check_motions, at the scene's edge resolution, in batches): free
//   milestones drawn from the seed (the first that the cpu backend finds free; it is
//   conservative, so they are free for every checker), each joined to its k nearest
//   under the scene's metric, undirected edges once each.
// The workload depends only on the scene, the table and the options, never on the
// checker, so every checker answers the same configurations or edges. Building it is
// not timed; one warm-up call (not recorded) precedes the timed ones.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "harness/bench_record.h"
#include "gplanner/planner/scene/scene.h"

namespace gplan {

struct QueryTableOptions {
  std::size_t queries = 50000;     // collision-queries: configurations per batch
  std::size_t milestones = 10000;  // local-planning: roadmap milestones (free ones)
  int neighbors = 15;              // local-planning: k nearest neighbours per milestone
  int repeat = 5;                  // timed batch calls per group
  std::uint64_t seed = 1;
};

// Measures one group: `table` is "collision-queries" or "local-planning", `checker`
// one of gpu-basic, gpu-packet, gpu-balanced, cpu, fcl (cpu and fcl on all cores).
// `repeat` timed calls, one BenchRecord each through `emit`: status "measured", run
// 0, 1, ..., seed options.seed, time_s the call as the caller sees it (wall clock),
// work = configurations or edges, collisions = colliding configurations or invalid
// edges, checker = the name of what actually ran (a gpu checker that fell back to the
// cpu backend says "cpu", the fallback in `note`). `experiment` and `scene_name` are
// copied into the records.
// Throws std::invalid_argument naming the accepted values for an unknown table or
// checker, or an option out of range; std::runtime_error when the scene's free space
// is too small to find the milestones, or when a timed call's verdicts differ from the
// warm-up's (a checker must answer the same batch the same way). Polls `should_stop`
// between calls and returns early, with fewer records, once it says so: the caller
// reports the interruption.
void run_query_group(const gplanner::Scene& scene, const std::string& experiment,
                     const std::string& scene_name, const std::string& table,
                     const std::string& checker, const QueryTableOptions& options,
                     const std::function<void(const BenchRecord&)>& emit,
                     const std::function<bool()>& should_stop);

// The checker names run_query_group accepts, in the seed's order: gpu-basic,
// gpu-packet, gpu-balanced, cpu, fcl.
const std::vector<std::string>& query_table_checkers();

// The table names run_query_group accepts: collision-queries, local-planning.
const std::vector<std::string>& query_tables();
// Whether a record's planner names one of query_tables() (not a planner).
bool is_query_table(const std::string& planner);

}  // namespace gplan
