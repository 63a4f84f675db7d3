#pragma once
// One point of the error-against-time study (a knob at one value with one checker) and
// its outputs: a CSV line (results.csv) and a row of the Markdown table (results.md).
//
// CSV columns: scene, knob, value, checker, time_s, missed, extra, undecided, total,
// runs, solved, path_fails, path_undecided. States and edges points leave the planning
// columns (runs ...) empty; planning points leave missed, extra and undecided empty.

#include <iosfwd>
#include <string>
#include <vector>

namespace gplan {

struct ErrorTimePoint {
  std::string scene;
  std::string knob;          // edge-resolution, max-displacement, certified-step, precision,
                             // traversal, delta, milestones, plan-edges
  std::string value;         // the knob's value as text (0.0025, gpu-packet, certified+certify)
  std::string checker;       // gpu, gpu-basic, gpu-packet, gpu-balanced, cpu, fcl
  double time_s = 0;         // states/edges: the median of the timed calls; planning: the
                             // median plan time over the runs
  long long missed = -1;     // truth colliding, reported free (-1: not applicable)
  long long extra = -1;      // truth free, reported colliding
  long long undecided = -1;  // edges the truth leaves undecided (excluded from both)
  long long total = 0;       // states, edges, or planning runs
  // Planning points (-1 elsewhere).
  long long runs = -1;
  long long solved = -1;
  long long path_fails = -1;      // returned paths that fail the ground truth
  long long path_undecided = -1;  // returned paths the ground truth leaves undecided

  bool planning() const { return runs >= 0; }
};

void write_error_time_csv_header(std::ostream& out);
void write_error_time_csv_line(std::ostream& out, const ErrorTimePoint& point);

// The Markdown table of all points, a section per scene, with `notices` (curves left
// out and why) under it.
void write_error_time_table(std::ostream& out, const std::string& experiment,
                            const std::vector<ErrorTimePoint>& points,
                            const std::vector<std::string>& notices);

// One line for the progress output: "piano edge-resolution 0.04 cpu: 12.3 ms, 3 missed,
// 0 extra of 1000 (5 undecided)".
std::string error_time_progress_line(const ErrorTimePoint& point);

}  // namespace gplan
