#include "ompl_log.h"

#include <ompl/base/PlannerStatus.h>
#include <ompl/config.h>
#include <ompl/tools/benchmark/MachineSpecs.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <ctime>
#include <map>
#include <ostream>
#include <stdexcept>
#include <utility>

#include "gplanner/planner/output/atomic_file.h"
#include "gplanner/planner/output/text_escaping.h"
#include "harness/bench_config.h"
#include "harness/query_runs.h"

namespace gplan {
namespace {

using ompl::base::PlannerStatus;

// The release of the OMPL we build with. Debian's OMPL 1.5 defines OMPL_VERSION as an
// empty string, so the version is put together from its parts.
std::string ompl_version() {
  return std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) + "." +
         std::to_string(OMPL_PATCH_VERSION);
}

// `text` on one line: control characters (newlines and carriage returns among them),
// line separators and invalid UTF-8 shown escaped (\n, \xNN), as on the terminal.
std::string one_line(const std::string& text) { return gplanner::terminal_text(text); }

// `text` as one word, for the lines of which the log's reader keeps only the last
// word (the experiment's name, the host): one_line with every kind of space Python's
// str.split() splits at (ASCII and Unicode) replaced by '_'; `fallback` when empty.
std::string one_word(const std::string& text, const char* fallback) {
  if (text.empty()) return fallback;
  static const char* const kUnicodeSpaces[] = {
      "\u00A0", "\u1680", "\u2000", "\u2001", "\u2002", "\u2003", "\u2004", "\u2005",
      "\u2006", "\u2007", "\u2008", "\u2009", "\u200A", "\u202F", "\u205F", "\u3000"};
  std::string word = one_line(text);
  for (const char* space : kUnicodeSpaces) {
    const std::string needle(space);
    for (std::size_t at = word.find(needle); at != std::string::npos; at = word.find(needle, at))
      word.replace(at, needle.size(), "_");
  }
  for (char& c : word)
    if (c == ' ') c = '_';
  return word;
}

// A property's value: one line, and no ';' (it separates a run's values, and the
// database keeps a planner's common properties joined by ';').
std::string property_value(const std::string& text) {
  std::string value = one_line(text);
  for (char& c : value)
    if (c == ';') c = ',';
  return value;
}

// A <<<| ... |>>> block's content: each line made one line of valid text, a line that
// would end the block early ("|>>>...") indented by a space, and a final newline (the
// reader looks for "|>>>" at the start of a line).
std::string block(const std::string& text) {
  std::string out;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    std::string line = one_line(text.substr(begin, end - begin));
    if (line.rfind("|>>>", 0) == 0) line = " " + line;
    out += line + "\n";
    begin = end + 1;
  }
  return out;
}

// A number as the shortest text that reads back as the same double; empty for NaN and
// infinities (not measured).
std::string number(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// An experiment's number, which the log's reader requires.
std::string required_number(double value, const char* what) {
  if (!std::isfinite(value))
    throw std::invalid_argument(std::string("OMPL log: the experiment's ") + what +
                                " is not a finite number");
  return number(value);
}

std::string count(long long value) { return value < 0 ? "" : std::to_string(value); }

std::string boolean(bool value) { return value ? "1" : "0"; }

// Names a record in an error message.
std::string describe(const BenchRecord& record) {
  return "the record of scene '" + one_line(record.scene) + "', planner '" +
         one_line(record.planner) + "', checker '" + one_line(record.checker) + "', run " +
         std::to_string(record.run);
}

[[noreturn]] void reject(const BenchRecord& record, const std::string& problem) {
  throw std::invalid_argument("OMPL log: " + describe(record) + ": " + problem);
}

bool is_planner(const std::string& planner) {
  const std::vector<std::string>& planners = bench_planners();
  return std::find(planners.begin(), planners.end(), planner) != planners.end();
}

// What each planning checker is, for the planner's common properties.
std::string checker_description(const BenchRecord& record) {
  if (record.checker == "fcl") return "FCL on the CPU (the baseline)";
  if (record.checker == "cpu") return "gplanner's exact triangle-mesh checker on the CPU";
  if (record.checker == "gpu") return "gplanner's exact triangle-mesh checker on the GPU";
  if (record.checker == "cpu-sampled")
    return "gplanner's exact triangle-mesh checker on the CPU, motions sampled";
  if (record.checker == "gpu-sampled")
    return "gplanner's exact triangle-mesh checker on the GPU, motions sampled";
  reject(record, "the checker '" + one_line(record.checker) +
                     "' is not one a planning run uses (fcl, cpu, gpu, cpu-sampled or "
                     "gpu-sampled)");
}

// BenchRecord::status as OMPL's PlannerStatus; an exception's run is OMPL's ABORT ("the
// planner did not find a solution for some other reason"; `note` says which). The log's
// enum line is OMPL's own PlannerStatus::asString, so it names the values as the OMPL
// we link does (1.5.2's asString has no case for ABORT and calls it "Unknown status").
PlannerStatus::StatusType ompl_status(const BenchRecord& record) {
  if (record.status == "exact") return PlannerStatus::EXACT_SOLUTION;
  if (record.status == "approximate") return PlannerStatus::APPROXIMATE_SOLUTION;
  if (record.status == "timeout") return PlannerStatus::TIMEOUT;
  if (record.status == "crash") return PlannerStatus::CRASH;
  if (record.status == "error") return PlannerStatus::ABORT;
  reject(record, "the status '" + one_line(record.status) +
                     "' is not one of a planning run (exact, approximate, timeout, crash, error)");
}

// The fine re-check with FCL as OMPL's "correct solution": 1, 0, or empty (no path).
std::string correct_solution(const BenchRecord& record) {
  if (record.path_check == "pass") return "1";
  if (record.path_check == "fail") return "0";
  if (record.path_check.empty()) return "";
  reject(record, "the path check '" + one_line(record.path_check) + "' is not pass, fail or empty");
}

using Properties = std::map<std::string, std::string>;  // "name TYPE" -> value, sorted

// One run's properties, named and typed as OMPL's Benchmark names them.
Properties run_properties(const BenchRecord& record) {
  const PlannerStatus::StatusType status = ompl_status(record);
  if (record.solved != (status == PlannerStatus::EXACT_SOLUTION))
    reject(record, "solved is " + std::string(record.solved ? "true" : "false") +
                       " but the status is '" + record.status + "'");
  const bool has_solution =
      status == PlannerStatus::EXACT_SOLUTION || status == PlannerStatus::APPROXIMATE_SOLUTION;
  return {
      {"time REAL", number(record.time_s)},
      {"solved BOOLEAN", boolean(record.solved)},
      {"status ENUM", std::to_string(static_cast<int>(status))},
      {"approximate solution BOOLEAN",
       has_solution ? boolean(status == PlannerStatus::APPROXIMATE_SOLUTION) : ""},
      {"solution length REAL", number(record.length)},
      {"simplified solution length REAL", number(record.simplified_length)},
      {"simplification time REAL", number(record.simplify_time_s)},
      {"correct solution BOOLEAN", correct_solution(record)},
      {"memory REAL", number(record.memory_mb)},
      {"graph states INTEGER", count(record.graph_states)},
      {"collision checks INTEGER", count(record.checks)},
      {"collision check time REAL", number(record.check_time_s)},
      {"seed INTEGER", std::to_string(record.seed)},
      {"note STRING", property_value(record.note)},
  };
}

// One planner of the log: a (planner, checker) pair and its runs.
struct LogPlanner {
  std::string name;
  Properties common;
  std::vector<Properties> runs;
};

std::vector<LogPlanner> log_planners(const std::vector<BenchRecord>& records) {
  std::vector<LogPlanner> planners;
  std::map<std::pair<std::string, std::string>, std::size_t> index;
  for (const BenchRecord& record : records) {
    if (is_query_table(record.planner)) continue;
    if (!is_planner(record.planner))
      reject(record,
             "the planner is none of ours-auto, ours-lazyprm, ours-prm, ours-rrtconnect, "
             "ompl-rrtconnect, ompl-prm, ompl-lazyprm, collision-queries, local-planning");
    const auto key = std::make_pair(record.planner, record.checker);
    auto found = index.find(key);
    if (found == index.end()) {
      found = index.emplace(key, planners.size()).first;
      planners.push_back({ompl_planner_name(record.planner, record.checker),
                          {{"planner STRING", record.planner},
                           {"checker STRING", record.checker},
                           {"checker description STRING", checker_description(record)}},
                          {}});
    }
    planners[found->second].runs.push_back(run_properties(record));
  }
  return planners;
}

void write_planner(std::ostream& out, const LogPlanner& planner) {
  out << planner.name << '\n';
  out << planner.common.size() << " common properties\n";
  for (const auto& [name, value] : planner.common) out << name << " = " << value << '\n';
  // Every run has the same properties (run_properties names them all).
  const Properties& first = planner.runs.front();
  out << first.size() << " properties for each run\n";
  for (const auto& property : first) out << property.first << '\n';
  out << planner.runs.size() << " runs\n";
  for (const Properties& run : planner.runs) {
    for (const auto& property : run) out << property.second << "; ";
    out << '\n';
  }
  out << ".\n";  // no progress data
}

}  // namespace

std::string ompl_planner_name(const std::string& planner, const std::string& checker) {
  static const std::map<std::string, std::string> kNames = {
      {"ompl-rrtconnect", "geometric_RRTConnect"}, {"ompl-prm", "geometric_PRM"},
      {"ompl-lazyprm", "geometric_LazyPRM"},       {"ours-auto", "gplanner_Auto"},
      {"ours-lazyprm", "gplanner_LazyPRM"},        {"ours-prm", "gplanner_PRM"},
      {"ours-rrtconnect", "gplanner_RRTConnect"}};
  const auto found = kNames.find(planner);
  if (found == kNames.end())
    throw std::invalid_argument("OMPL log: the planner '" + one_line(planner) + "' is none of " +
                                "ours-auto, ours-lazyprm, ours-prm, ours-rrtconnect, "
                                "ompl-rrtconnect, ompl-prm, ompl-lazyprm");
  return found->second + "_" + one_word(checker, "unknown");
}

void write_ompl_log(std::ostream& out, const OmplLogExperiment& experiment,
                    const std::vector<BenchRecord>& records) {
  // Everything checked before anything is written.
  const std::vector<LogPlanner> planners = log_planners(records);
  const std::string time_limit = required_number(experiment.time_limit_s, "time limit");
  const std::string memory_limit = required_number(experiment.memory_limit_mb, "memory limit");
  const std::string total_time = required_number(experiment.total_seconds, "total time");
  out << "OMPL version " << ompl_version() << '\n';
  out << "Experiment " << one_word(experiment.name, "NO_NAME") << '\n';
  out << "0 experiment properties\n";
  out << "Running on " << one_word(experiment.host, "UNKNOWN") << '\n';
  out << "Starting at " << one_line(experiment.date) << '\n';
  out << "<<<|\n" << block(experiment.setup) << "|>>>\n";
  out << "<<<|\n" << block(experiment.cpu_info) << "|>>>\n";
  out << experiment.seed << " is the random seed\n";
  out << time_limit << " seconds per run\n";
  out << memory_limit << " MB per run\n";
  out << experiment.runs_per_planner << " runs per planner\n";
  out << total_time << " seconds spent to collect the data\n";
  out << "1 enum type\n";
  out << "status";
  for (int i = 0; i < PlannerStatus::TYPE_COUNT; ++i)
    out << '|' << PlannerStatus(static_cast<PlannerStatus::StatusType>(i)).asString();
  out << '\n';
  out << planners.size() << " planners\n";
  for (const LogPlanner& planner : planners) write_planner(out, planner);
}

void write_ompl_log_file(const std::string& path, const OmplLogExperiment& experiment,
                         const std::vector<BenchRecord>& records) {
  gplanner::write_file_atomically(
      path, [&](std::ostream& out) { write_ompl_log(out, experiment, records); });
}

std::string ompl_host_name() { return ompl::machine::getHostname(); }

std::string ompl_cpu_info() { return ompl::machine::getCPUInfo(); }

std::string local_date_time() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%S", &local);
  return text;
}

}  // namespace gplan
