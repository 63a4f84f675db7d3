#pragma once
// The error-against-time study of `gplan-bench` (kind: error-time): for each scene, every
// speed knob swept and each of its values measured for run time and for error against a
// ground truth from FCL in double precision (benchmarks/harness/error_time_truth.h), on the
// checkers the configuration names. See benchmarks/README.md, "Error against time".
//
// Knobs (curves), each point one knob value with one checker:
// - states (N seeded random states, one batch call timed): precision (the gpu and cpu
//   backends in float, and FCL itself in double), traversal (gpu-basic, gpu-packet,
//   gpu-balanced), delta (the tolerance band, planner.delta_fraction, on gpu and cpu);
//   error: states missed (truth colliding, reported free) and extra (truth free,
//   reported colliding);
// - edges (M seeded roadmap-like edges, benchmarks/harness/error_time_workload.h, one batch of
//   all of them timed): edge-resolution (LocalPlanner's sampled edges at multiples of
//   the scene's resolution; max-displacement for scenes that set it) and certified-step
//   (CertifiedMotions at several first steps); error: edges missed and extra, the edges
//   the truth leaves undecided excluded;
// - planning (ours-lazyprm, `runs` seeded runs a point): milestones (first-round counts)
//   and plan-edges (PlanOptions.edges sampled or certified, certify_path on and off);
//   the median plan time, runs solved, and returned paths that fail the ground truth.
// A gpu that cannot be used here leaves its curves out with a notice: its name is never
// put on the cpu backend's times.

#include <functional>
#include <string>
#include <vector>

#include "harness/bench_config.h"
#include "harness/error_time_record.h"

namespace gplanner {
struct Scene;
}

namespace gplan {

// The study on one scene: each point through `emit` as it is measured, each curve left
// out (and why) through `notice`, progress lines (the ground truth's making) through
// `progress`. Returns early, with fewer points, once `stop` says so. Throws
// std::runtime_error when the scene's free space is too small for the edges' milestones.
void run_error_time_scene(const gplanner::Scene& scene, const std::string& scene_name,
                          const BenchConfig& config,
                          const std::function<void(const ErrorTimePoint&)>& emit,
                          const std::function<void(const std::string&)>& notice,
                          const std::function<void(const std::string&)>& progress,
                          const std::function<bool()>& stop);

// `gplan-bench` for a configuration of kind error-time, the scenes loaded and the output
// folder `dir` made (new or empty): runs the study on every scene with progress on
// stderr and writes into `dir` results.csv (results.partial.csv while it runs),
// results.md (the table), config.yaml (the configuration as read) and, where `plots`,
// plots/<scene>.png and .svg. Returns the exit code: 0, or 128 + the signal when
// `should_stop` said so (the points done are kept in results.partial.csv).
int run_error_time_study(const BenchConfig& config, const std::vector<gplanner::Scene>& scenes,
                         const std::string& dir, bool plots,
                         const std::function<bool()>& should_stop);

}  // namespace gplan
