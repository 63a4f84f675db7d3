#pragma once
// Baselines of `gplan-bench` and the verdict against one.
//
// A baseline file (YAML, written by --save-baseline) keeps each group's summary: runs,
// success rate, median time (with the time a run without a path took counted in) and
// median path length. A run is compared group by group with the tolerances of its
// configuration (BenchTolerances): slower by more than time_ratio (and by more than
// time_floor seconds), a success rate lower by more than success_rate, paths longer by
// more than path_length_ratio, or a group of the baseline missing from the run: each is
// a regression. Times are compared as measured, so a baseline is meant for the machine
// it was measured on (or one like it: widen time_ratio otherwise).

#include <string>
#include <vector>

#include "harness/bench_config.h"
#include "harness/bench_summary.h"

namespace gplan {

// Writes `groups` as a baseline (atomically; the caller has checked the path).
void save_baseline(const std::string& file, const std::string& config_file,
                   const std::vector<GroupSummary>& groups);

// Reads a baseline; throws gplanner::InputError naming the file, line and key.
std::vector<GroupSummary> load_baseline(const std::string& file);

struct BaselineVerdict {
  std::vector<std::string> regressions;  // one line each: group, metric, figures, tolerance
  std::vector<std::string> notes;        // groups without a baseline, and the like
  bool regressed() const { return !regressions.empty(); }
};

BaselineVerdict compare_with_baseline(const std::vector<GroupSummary>& run,
                                      const std::vector<GroupSummary>& baseline,
                                      const BenchTolerances& tolerances);

}  // namespace gplan
