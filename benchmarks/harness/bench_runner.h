#pragma once
// Runs the groups of a `gplan-bench` configuration, each in a worker process of its own.
//
// A group is one scene with one planner@checker (planning) or one query table with one
// checker (queries); its runs go one after another in its worker. Workers are forked
// from gplan after the scenes are loaded (they share them); the parent never touches
// the GPU, so each worker that needs it makes its own CUDA context. A worker's crash,
// or a run far past its time limit (killed), costs that run (recorded as "crash"), not
// the benchmark. Groups that use several cores (ours, the cpu backend, the query tables)
// run alone; OMPL's planners on one planning thread (PlannerChoice::single_threaded) run
// up to `jobs` at a time, at most one of them on the GPU, whose checker answers small
// calls on the cores the others leave (all cores less `jobs` - 1).

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "harness/bench_config.h"
#include "harness/bench_record.h"

namespace gplanner {
struct Scene;
}

namespace gplan {

struct BenchGroup {
  std::size_t scene = 0;  // index into the configuration's scenes
  std::string scene_name;
  PlannerChoice choice;  // planning
  std::string table;     // queries: collision-queries or local-planning
  std::string checker;   // queries
  int first_run = 0;     // the run number of its first run (a problem set's problem index)
  int runs = 0;          // runs planned (planning: config.runs; queries: config.repeat)
  bool alone = true;     // runs with no other group beside it
  bool gpu = false;      // one planning thread and the GPU (at most one such at a time)
  std::string label() const;
};

// The configuration's groups in the order they start: those that run alone first (scene
// by scene), then the single-threaded ones (each as soon as it may).
std::vector<BenchGroup> bench_groups(const BenchConfig& config);

// Runs every group; returns all records, in the order of `groups` and run. Shows
// progress on `progress` (a line per run) and hands each record to `on_record` as it
// comes. `should_stop` (a signal) stops it: running workers are told to stop, and the
// records so far are returned. Paths that fail the FCL re-check are kept in
// `failed_paths_dir`.
std::vector<BenchRecord> run_bench_groups(const BenchConfig& config,
                                          const std::vector<gplanner::Scene>& scenes,
                                          const std::vector<BenchGroup>& groups, int jobs,
                                          std::ostream& progress,
                                          const std::function<bool()>& should_stop,
                                          const std::function<void(const BenchRecord&)>& on_record,
                                          const std::string& failed_paths_dir);

}  // namespace gplan
