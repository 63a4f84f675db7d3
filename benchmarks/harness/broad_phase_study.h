#pragma once
// The sphere broad-phase study of `gplan-bench` (kind: broad-phase): the seed's Table I
// (all pairs, sequential on the CPU against parallel on the GPU, 64 to 320 spheres,
// average FPS and speed-up) and beyond it, the scalable methods up to a million spheres.
//
// At each count, n seeded spheres bounce in a box (benchmarks/harness/broad_phase_motion.h); each
// frame moves them, then every method finds the frame's pairs, timed from the spheres on
// the host to the pairs on the host (the GPU methods' transfers included). Every method's
// pair set is compared, frame by frame, with the reference's: the first method of
// cpu-all-pairs, cpu-sort-sweep, gpu-all-pairs, gpu-sort-sweep, gpu-grid, gpu-lbvh that runs
// at the count. One untimed warm-up frame per count (a GPU's first allocations). A method runs at
// a count up to its max_count; gpu methods are left out, with a notice, where no GPU can
// be used. See benchmarks/README.md, "Broad phase".

#include <functional>
#include <string>

#include "harness/bench_config.h"

namespace gplan {

// Runs the study with progress on stderr and writes into `dir` (made, new or empty)
// results.csv (results.partial.csv while it runs), results.md (the tables, also printed),
// config.yaml and, where `plots`, plots/broad_phase.png and .svg. Returns the exit code:
// 0; 3 when a method's pairs differed from the reference's in some frame, or a method
// failed; 128 + the signal when `should_stop` said so between frames (the counts done
// kept in results.partial.csv).
int run_broad_phase_study(const BenchConfig& config, const std::string& dir, bool plots,
                          const std::function<bool()>& should_stop);

}  // namespace gplan
