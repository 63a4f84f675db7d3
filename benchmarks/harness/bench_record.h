#pragma once
// One measured run of `gplan-bench`: a planning run (one planner on one scene with one
// seed) or one timed batch of the seed's query tables (collision queries or local
// planning). Records are what the CSV holds, one per line, and what the OMPL log, the
// summary, the plots and the baseline verdict are made from.

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

namespace gplan {

inline constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

struct BenchRecord {
  std::string experiment;  // the configuration's name
  std::string scene;       // the scene's name (its file's stem)
  // Planning: ours-auto, ours-lazyprm, ours-prm, ours-rrtconnect, ompl-rrtconnect,
  // ompl-prm, ompl-lazyprm.
  // Query tables: "collision-queries" (milestone computation) or "local-planning".
  std::string planner;
  // The checker that actually ran: fcl, cpu, gpu; for the query tables the gpu
  // traversal too (gpu-basic, gpu-packet, gpu-balanced).
  std::string checker;
  int run = 0;             // 0, 1, ... within its (scene, planner, checker) group
  std::uint64_t seed = 0;  // the run's own seed
  // exact, approximate, timeout (no path in the time limit), crash (the run's process
  // ended without a result), error (an exception; `note` says which), measured (a
  // query-table batch).
  std::string status;
  bool solved = false;  // planning: an exact solution was returned
  double time_s = kNotMeasured;  // planning: the solve; query tables: the batch call
  // OMPL's planners: SimplifySolution after the solve, timed apart (as OMPL's
  // Benchmark does); ours: their shortcutting (part of time_s).
  double simplify_time_s = kNotMeasured;
  double length = kNotMeasured;             // the returned path before simplification
  double simplified_length = kNotMeasured;  // and after it (ours: after shortcutting)
  long long checks = -1;        // state checks (planning) as the planner counted them
  // OMPL's planners: the part of time_s spent in collision checks (the validity checker
  // and the motion validator, timed where the planner calls them).
  double check_time_s = kNotMeasured;
  long long graph_states = -1;  // roadmap or tree vertices at the end of the run
  double memory_mb = kNotMeasured;  // peak resident memory of the run's process
  // The fine re-check of a returned path with FCL: "pass", "fail", or empty (no path).
  std::string path_check;
  long long work = -1;        // query tables: configurations or edges in the batch
  long long collisions = -1;  // query tables: of them, found colliding (or invalid)
  // Our planners: where time_s went, stage by stage (PlanTimes; shortcutting is
  // simplify_time_s), and the roadmap's rounds. Not measured for OMPL's planners.
  double sampling_s = kNotMeasured;
  double state_checks_s = kNotMeasured;
  double knn_s = kNotMeasured;
  double search_s = kNotMeasured;
  double edge_checks_s = kNotMeasured;
  long long rounds = -1;
  long long gpu_calls = -1;  // our planners: GPU calls of the plan (PlanGpuCalls::total)
  // The CUDA device the run's checker used (numbered among those gplan-bench saw); -1
  // where it used none (fcl, cpu).
  long long device = -1;
  std::string note;  // free text: a fallback, an error message, a re-check failure
};

// The CSV header line's fields, in order.
const std::vector<std::string>& bench_csv_columns();

// Writes the header line.
void write_bench_csv_header(std::ostream& out);
// Writes one record as a CSV line (RFC 4180 quoting where a field needs it; NaN and -1
// as empty fields).
void write_bench_csv_line(std::ostream& out, const BenchRecord& record);
// One record from one line as write_bench_csv_line writes it (its newline optional);
// throws std::runtime_error naming the column at fault.
BenchRecord parse_bench_csv_record(const std::string& text);
// Reads a CSV written by write_bench_csv_* (also those of earlier versions: without
// device, until issue 36; without gpu_calls, in issue 33's first figures; without the stage
// columns, until issue 33; without check_time_s, until issue 22); throws std::runtime_error naming
// the file, line and column on anything else.
std::vector<BenchRecord> read_bench_csv(const std::string& file);

}  // namespace gplan
