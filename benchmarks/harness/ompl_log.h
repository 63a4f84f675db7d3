#pragma once
// OMPL's benchmark log, as ompl::tools::Benchmark::saveResultsToStream writes it (OMPL
// 1.5), made from `gplan-bench`'s planning records: OMPL's ompl_benchmark_statistics
// reads it into the Planner Arena database (experiments, plannerConfigs, runs, enums).
// One log holds one experiment (one scene); every (planner, checker) is one "planner".

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "harness/bench_record.h"

namespace gplan {

struct OmplLogExperiment {
  std::string name;                  // the experiment's name, e.g. "regression: piano"
  std::string setup;                 // free text: the scene file, its settings, the config
  std::string host, cpu_info, date;  // cpu_info may be empty
  std::uint64_t seed = 0;            // the first run's seed
  double time_limit_s = 0, memory_limit_mb = 0, total_seconds = 0;
  int runs_per_planner = 0;
};

// The planner's name in the log, as OMPL names its planners with the checker added:
// ompl-rrtconnect, ompl-prm, ompl-lazyprm as geometric_RRTConnect, geometric_PRM,
// geometric_LazyPRM; ours-lazyprm, ours-prm as gplanner_LazyPRM, gplanner_PRM; e.g.
// "geometric_RRTConnect_fcl", "gplanner_LazyPRM_gpu". Throws std::invalid_argument for
// a planner that is not one of those.
std::string ompl_planner_name(const std::string& planner, const std::string& checker);

// Writes one experiment in OMPL's log format: every planning record of `records` (the
// caller passes one scene's; query-table records are left out), grouped by (planner,
// checker) into one planner each, in the order they first appear. Run properties carry
// OMPL's names and types (time REAL, solved BOOLEAN, status ENUM, ...); unmeasured
// values are empty fields (NULL in the database). Text from the user (names, setup,
// notes) is made safe for the format: one line where the format wants one (control
// characters shown as \n, \xNN), no "; " that would split a run's values, no line of
// the setup starting "|>>>", single words where the reader keeps only the last word.
// Throws std::invalid_argument for a planning record with an unknown planner, checker,
// status or path_check (naming the record).
void write_ompl_log(std::ostream& out, const OmplLogExperiment& experiment,
                    const std::vector<BenchRecord>& records);

// write_ompl_log into the file at `path`, written whole or not at all
// (gplanner::write_file_atomically); throws std::runtime_error naming the file.
void write_ompl_log_file(const std::string& path, const OmplLogExperiment& experiment,
                         const std::vector<BenchRecord>& records);

// This machine as OMPL's MachineSpecs describes it: the host name, and the CPU (OMPL
// 1.5 on Linux: what `lscpu` prints; empty where it cannot run).
std::string ompl_host_name();
std::string ompl_cpu_info();
// The local date and time now, as "2024-05-01T13:45:07" (one word, as the log wants).
std::string local_date_time();

}  // namespace gplan
