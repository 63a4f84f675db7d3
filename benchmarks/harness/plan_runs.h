#pragma once
// The planning runs of `gplan-bench`: one (scene, planner@checker) group at a time.
//
// Every run is a fresh planner with its own seed (the configuration's seed + the run's
// index): ours take it as their seed; for OMPL's, OMPL's random number generator is
// seeded with it before the run's SimpleSetup and planner exist, so the run's samplers
// draw from it. OMPL's planners run as their users run them: one planning thread,
// OMPL's default settings, SimpleSetup with our state space (the planner's metric and
// motion resolution), and either our FCL backend on the planning thread with OMPL's
// DiscreteMotionValidator (@fcl: the baseline, FCL on the CPU) or our validity checker
// and batched motion validator on a backend (@cpu, @gpu: the OMPL plugin). After a solve
// OMPL's planners simplify the path (simplifySolution, timed apart, as OMPL's Benchmark
// does); ours shortcut within their own time. Every returned path is re-checked with FCL
// at a finer resolution (gplanner::path_recheck_problem); one that fails is also checked
// at the planner's own resolution (is the collision between its samples?), and written
// as a path file into `failed_paths_dir` (when not empty) for a closer look.

#include <functional>
#include <string>

#include "harness/bench_config.h"
#include "harness/bench_record.h"

namespace gplanner {
struct Scene;
}

namespace gplan {

// Runs the group's runs, calling `emit` with each run's record as it ends. Stops early
// (the remaining runs not run) when the group has spent config.group_budget_s or when
// `should_stop` says so (it is also polled during a solve). `notice` receives what the
// user should know once (the k-NN's fallback). A gpu checker that would run on the cpu
// backend (no GPU here) throws: its times would be the cpu's under a gpu name.
// host_threads: the host threads our checker may use (0: all cores); device: the CUDA
// device of a gpu checker (and its record's `device`). Records are named
// `scene_name` and numbered from `first_run` (a problem set: the problem's index).
void run_planning_group(const gplanner::Scene& scene, const std::string& scene_name, int first_run,
                        const BenchConfig& config, const PlannerChoice& choice, int host_threads,
                        int device, const std::function<void(const BenchRecord&)>& emit,
                        const std::function<bool()>& should_stop,
                        const std::function<void(const std::string&)>& notice,
                        const std::string& failed_paths_dir);

}  // namespace gplan
