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
// up to `jobs` at a time, at most one of them on each GPU, whose checker answers small
// calls on the cores the others leave (all cores less `jobs` - 1).
//
// Our planners on the gpu backend run on serving workers: one per GPU, forked once, each
// running such groups one after another as they come, so that its CUDA context (a few
// tenths of a second to start, more than an easy problem's plan) serves them all; one
// whose group ended in an error, or that is idle when the next group is of another kind,
// ends. Each worker of a group on the gpu backend has one GPU of its own (the lowest
// free one), named in its progress line and in its records' `device`. With several GPUs
// our planners run one per GPU at a time, side by side, each with an equal share of the
// cores; the other groups that run alone still run alone.

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
  bool gpu = false;      // planning on the gpu backend (a GPU of its own)
  std::string label() const;
};

// The configuration's groups in the order they start: those that run alone first (scene
// by scene), then the single-threaded ones (each as soon as it may).
std::vector<BenchGroup> bench_groups(const BenchConfig& config);

// How the workers share the machine.
struct BenchResources {
  int jobs = 1;     // single-threaded groups at a time (--jobs)
  int gpus = 1;     // GPUs the gpu groups are spread over, devices 0 to gpus - 1
  int threads = 0;  // host threads of every group (--threads); 0: as said above
};

// Where single-threaded groups ran side by side (`jobs` above 1, two or more such
// groups), a notice saying what that does to their times: each is slower than when run
// alone, as its users run it (measured on a 16-core H200 host, MotionBenchMaker's first
// 20 problems per scenario: OMPL's RRTConnect with FCL 1.1x to 1.9x slower 12 at a time
// than one at a time), so that ratios against them flatter the groups that ran alone.
// Empty otherwise.
std::string side_by_side_notice(const std::vector<BenchGroup>& groups, int jobs);

// The CUDA devices this machine shows gplan-bench, counted in a child process (the
// parent never initialises CUDA: its forked workers could not use it); 0 where none.
int count_gpus_in_child();

// Runs every group; returns all records, in the order of `groups` and run. Shows
// progress on `progress` (a line per run) and hands each record to `on_record` as it
// comes. `should_stop` (a signal) stops it: running workers are told to stop, and the
// records so far are returned. Paths that fail the FCL re-check are kept in
// `failed_paths_dir`.
std::vector<BenchRecord> run_bench_groups(const BenchConfig& config,
                                          const std::vector<gplanner::Scene>& scenes,
                                          const std::vector<BenchGroup>& groups,
                                          const BenchResources& resources, std::ostream& progress,
                                          const std::function<bool()>& should_stop,
                                          const std::function<void(const BenchRecord&)>& on_record,
                                          const std::string& failed_paths_dir);

}  // namespace gplan
