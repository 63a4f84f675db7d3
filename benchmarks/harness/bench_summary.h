#pragma once
// What a `gplan-bench` run comes to, group by group: the summary table printed in the
// terminal and written to summary.txt, and what a baseline keeps.

#include <iosfwd>
#include <string>
#include <vector>

#include "harness/bench_record.h"

namespace gplan {

struct GroupSummary {
  std::string experiment, scene, planner, checker;
  int runs = 0;
  int solved = 0;                // planning: exact solutions
  double success_rate = 0;       // solved / runs (query tables: 1)
  // Times over every run, a run without a path counted at its full time (so the median
  // is a lower bound, median_is_lower_bound, when half the runs or more found none).
  double median_time_s = 0, q1_time_s = 0, q3_time_s = 0, min_time_s = 0, max_time_s = 0;
  bool median_is_lower_bound = false;
  // Median length of the returned paths (after simplification where there was one);
  // NaN with no path.
  double median_length = 0;
  // OMPL's planners: the median over runs of the share of the plan time spent in
  // collision checks (check_time_s / time_s); NaN where not measured.
  double median_check_share = 0;
  int paths_checked = 0;   // returned paths re-checked with FCL
  int path_failures = 0;   // of them, those that failed
  int crashes = 0;         // runs with status crash or error
  // The FCL baseline this group is set against: the same planner with FCL on the CPU
  // where the run has it, otherwise the fastest FCL group of the scene (the fcl checker
  // of the same table, for the query tables); its median over this group's (how many
  // times faster this group is); NaN where there is none.
  std::string reference;
  double speedup_over_fcl = 0;
  bool reference_is_lower_bound = false;  // its median too
  std::string key() const { return scene + " " + planner + "@" + checker; }
};

// Groups in the order of their first record.
std::vector<GroupSummary> summarize(const std::vector<BenchRecord>& records);

// The summary table: one row per group, aligned columns, for the terminal and
// summary.txt.
void print_summary(std::ostream& out, const std::vector<GroupSummary>& groups);

// A problem set's table (motionbenchmaker.h): per scenario and planner@checker, problems
// solved / valid / total (VAMP's form), success over the valid ones, the median and p95
// time; then the invalid problems and why.
void print_problem_set_summary(std::ostream& out, const std::vector<BenchRecord>& records);

// Where our planners' time goes (records with stage times): per scene and
// planner@checker, over the solved runs, the median plan time and the median of each
// stage (sampling, state checks, k-NN, search, edge checks, shortcutting, and what the
// plan time holds beyond them), and the median rounds. Nothing when no record has them.
void print_stage_summary(std::ostream& out, const std::vector<BenchRecord>& records);

// The median of `values` (NaN when empty).
double median_of(std::vector<double> values);

}  // namespace gplan
