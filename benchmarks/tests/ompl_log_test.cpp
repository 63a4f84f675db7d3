// The OMPL benchmark log of `gplan bench` read by OMPL's own ompl_benchmark_statistics
// (ompl-demos, installed by scripts/setup.sh) into the Planner Arena database, which is
// then read back with Python's sqlite3; and the log's text where names are hostile.

#include "harness/ompl_log.h"

#include <gtest/gtest.h>
#include <ompl/config.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "test_support.h"

namespace gplan {
namespace {

using gplanner::testing::read_file;
using gplanner::testing::ScratchFolder;
using gplanner::testing::shell_quoted;

using Row = std::vector<std::string>;  // a database row, NULL as "NULL"

// The whole standard output of `command` (and its exit status).
std::string output_of(const std::string& command, int* status) {
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    *status = -1;
    return output;
  }
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0;)
    output.append(buffer, n);
  *status = pclose(pipe);
  return output;
}

// Where OMPL's ompl_benchmark_statistics is, or empty.
std::string statistics_program() {
  int status = 0;
  std::string found = output_of("command -v ompl_benchmark_statistics", &status);
  while (!found.empty() && (found.back() == '\n' || found.back() == '\r')) found.pop_back();
  return status == 0 ? found : "";
}

// Loads `log` into a fresh database in `folder` with ompl_benchmark_statistics and
// returns the database's path; fails the test (not skips) when the program is missing.
std::string load_into_database(const ScratchFolder& folder, const std::string& log) {
  const std::string program = statistics_program();
  EXPECT_FALSE(program.empty())
      << "ompl_benchmark_statistics is not installed: it is part of the project's "
         "dependencies (Debian's ompl-demos, installed by scripts/setup.sh)";
  if (program.empty()) return "";
  const std::string database = folder.path() + "/benchmark.db";
  const std::string console = folder.path() + "/statistics.txt";
  const int status =
      std::system(("timeout 120 " + shell_quoted(program) + " " + shell_quoted(log) + " -d " +
                   shell_quoted(database) + " > " + shell_quoted(console) + " 2>&1")
                      .c_str());
  EXPECT_EQ(status, 0) << read_file(console);
  return status == 0 ? database : "";
}

// The rows of `sql` on `database`, read with Python's sqlite3 (Python 3 comes with
// ompl_benchmark_statistics, which is a Python program): NULL as "NULL", fields and
// rows parted by the ASCII unit and record separators (the values hold newlines).
std::vector<Row> query(const ScratchFolder& folder, const std::string& database,
                       const std::string& sql) {
  const std::string script = folder.write("query.py",
                                          "import sqlite3, sys\n"
                                          "connection = sqlite3.connect(sys.argv[1])\n"
                                          "sql = open(sys.argv[2]).read()\n"
                                          "for row in connection.execute(sql):\n"
                                          "    print('\\x1f'.join('NULL' if v is None else str(v)"
                                          " for v in row), end='\\x1e')\n");
  const std::string sql_file = folder.write("query.sql", sql);
  int status = 0;
  const std::string output =
      output_of("/usr/bin/python3 " + shell_quoted(script) + " " + shell_quoted(database) + " " +
                    shell_quoted(sql_file) + " 2>&1",
                &status);
  EXPECT_EQ(status, 0) << sql << "\n" << output;
  std::vector<Row> rows;
  std::size_t begin = 0;
  for (std::size_t end; (end = output.find('\x1e', begin)) != std::string::npos; begin = end + 1) {
    const std::string line = output.substr(begin, end - begin);
    Row row;
    std::size_t field = 0;
    for (std::size_t unit; (unit = line.find('\x1f', field)) != std::string::npos; field = unit + 1)
      row.push_back(line.substr(field, unit - field));
    row.push_back(line.substr(field));
    rows.push_back(row);
  }
  EXPECT_EQ(begin, output.size()) << "not rows: " << output.substr(begin);
  return rows;
}

BenchRecord planning_record(const std::string& planner, const std::string& checker, int run,
                            const std::string& status) {
  BenchRecord record;
  record.experiment = "regression";
  record.scene = "piano";
  record.planner = planner;
  record.checker = checker;
  record.run = run;
  record.seed = 1000 + 10 * run + (checker == "fcl" ? 1 : 2) + (planner == "ours-lazyprm" ? 5 : 0);
  record.status = status;
  record.solved = status == "exact";
  record.memory_mb = 40.5 + run;
  record.checks = 1000 * (run + 1);
  record.graph_states = 50 * (run + 1);
  if (status == "exact" || status == "approximate") {
    record.time_s = 0.125 * (run + 1);
    record.length = 3.5 + run;
    record.simplified_length = 2.25 + run;
    record.simplify_time_s = 0.0625;
    record.path_check = status == "exact" ? "pass" : "fail";
  } else if (status == "timeout") {
    record.time_s = 5.0;
  } else if (status == "crash") {
    record.checks = -1;  // nothing came back from the run's process
    record.graph_states = -1;
    record.memory_mb = gplan::kNotMeasured;
    record.note = "the run's process ended with signal 11";
  }
  return record;
}

// Two planners by two checkers, each with an exact, an unsolved and a crashed run (and
// an approximate run and an error for one), with a query-table record among them.
std::vector<BenchRecord> scene_records() {
  std::vector<BenchRecord> records;
  for (const std::string planner : {"ompl-rrtconnect", "ours-lazyprm"})
    for (const std::string checker : {"fcl", "gpu"}) {
      records.push_back(planning_record(planner, checker, 0, "exact"));
      records.push_back(planning_record(planner, checker, 1, "timeout"));
      records.push_back(planning_record(planner, checker, 2, "crash"));
    }
  records.push_back(planning_record("ompl-rrtconnect", "fcl", 3, "approximate"));
  BenchRecord error = planning_record("ours-lazyprm", "gpu", 3, "error");
  error.note = "out of GPU memory";
  records.push_back(error);
  BenchRecord queries;
  queries.scene = "piano";
  queries.planner = "collision-queries";
  queries.checker = "gpu-packet";
  queries.status = "measured";
  queries.time_s = 0.01;
  records.push_back(queries);
  return records;
}

OmplLogExperiment piano_experiment() {
  OmplLogExperiment experiment;
  experiment.name = "regression-piano";
  experiment.setup = "scene: scenes/piano.yaml\nconfig: benchmarks/config/regression.yaml\n";
  experiment.host = "bench-host";
  experiment.cpu_info = "Model name: Test CPU\n";
  experiment.date = "2024-05-01T13:45:07";
  experiment.seed = 1001;
  experiment.time_limit_s = 5;
  experiment.memory_limit_mb = 4096;
  experiment.total_seconds = 42.5;
  experiment.runs_per_planner = 3;
  return experiment;
}

std::string ompl_version() {
  return std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) + "." +
         std::to_string(OMPL_PATCH_VERSION);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The expected database text of a number ("NULL" when not measured), as Python prints
// the REAL it reads back.
void expect_real(const std::string& field, double expected, const std::string& what) {
  if (std::isnan(expected)) {
    EXPECT_EQ(field, "NULL") << what;
  } else {
    ASSERT_NE(field, "NULL") << what;
    EXPECT_DOUBLE_EQ(std::stod(field), expected) << what;
  }
}

TEST(OmplLog, OmplBenchmarkStatisticsLoadsEveryRunIntoThePlannerArenaDatabase) {
  ScratchFolder folder;
  const std::vector<BenchRecord> records = scene_records();
  const std::string log = folder.path() + "/piano.log";
  write_ompl_log_file(log, piano_experiment(), records);
  const std::string database = load_into_database(folder, log);
  ASSERT_FALSE(database.empty());

  const std::vector<Row> experiments =
      query(folder, database,
            "SELECT name, timelimit, memorylimit, runcount, totaltime, version, hostname, seed, "
            "date, setup, cpuinfo FROM experiments");
  ASSERT_EQ(experiments.size(), 1u);
  EXPECT_EQ(experiments[0][0], "regression-piano");
  EXPECT_EQ(experiments[0][1], "5.0");
  EXPECT_EQ(experiments[0][2], "4096.0");
  EXPECT_EQ(experiments[0][3], "3");
  EXPECT_EQ(experiments[0][4], "42.5");
  EXPECT_EQ(experiments[0][5], "OMPL " + ompl_version());
  EXPECT_EQ(experiments[0][6], "bench-host");
  EXPECT_EQ(experiments[0][7], "1001");
  EXPECT_EQ(experiments[0][8], "2024-05-01T13:45:07");
  EXPECT_EQ(experiments[0][9], "scene: scenes/piano.yaml\nconfig: benchmarks/config/regression.yaml\n");
  EXPECT_EQ(experiments[0][10], "Model name: Test CPU\n");

  const std::vector<Row> planners =
      query(folder, database, "SELECT name, settings FROM plannerConfigs ORDER BY id");
  ASSERT_EQ(planners.size(), 4u);
  EXPECT_EQ(planners[0][0], "geometric_RRTConnect_fcl");
  EXPECT_EQ(planners[1][0], "geometric_RRTConnect_gpu");
  EXPECT_EQ(planners[2][0], "gplanner_LazyPRM_fcl");
  EXPECT_EQ(planners[3][0], "gplanner_LazyPRM_gpu");
  EXPECT_NE(planners[0][1].find("checker STRING = fcl"), std::string::npos) << planners[0][1];
  EXPECT_NE(planners[0][1].find("checker description STRING = FCL on the CPU"), std::string::npos);
  EXPECT_NE(planners[0][1].find("planner STRING = ompl-rrtconnect"), std::string::npos);
  EXPECT_NE(planners[3][1].find("checker STRING = gpu"), std::string::npos) << planners[3][1];

  // OMPL's status enum, as its own Benchmark writes it.
  const std::vector<Row> statuses =
      query(folder, database,
            "SELECT value, description FROM enums WHERE name = 'status' ORDER BY value");
  ASSERT_EQ(statuses.size(), 9u);  // OMPL 1.5: UNKNOWN .. ABORT
  EXPECT_EQ(statuses[4][1], "Timeout");
  EXPECT_EQ(statuses[5][1], "Approximate solution");
  EXPECT_EQ(statuses[6][1], "Exact solution");
  EXPECT_EQ(statuses[7][1], "Crash");

  // One row per planning record (the query-table record left out), found by its seed.
  const std::vector<Row> runs = query(
      folder, database,
      "SELECT plannerConfigs.name, seed, time, solved, status, approximate_solution, "
      "correct_solution, solution_length, simplified_solution_length, simplification_time, "
      "memory, graph_states, collision_checks, note, experimentid FROM runs JOIN plannerConfigs "
      "ON runs.plannerid = plannerConfigs.id");
  ASSERT_EQ(runs.size(), records.size() - 1);
  std::map<std::string, Row> by_seed;
  for (const Row& run : runs) by_seed[run[1]] = run;
  ASSERT_EQ(by_seed.size(), runs.size()) << "seeds repeat";
  const std::map<std::string, int> enum_value = {
      {"timeout", 4}, {"approximate", 5}, {"exact", 6}, {"crash", 7}, {"error", 8}};
  for (const BenchRecord& record : records) {
    if (record.planner == "collision-queries") continue;
    const std::string what =
        record.planner + " " + record.checker + " run " + std::to_string(record.run);
    ASSERT_EQ(by_seed.count(std::to_string(record.seed)), 1u) << what;
    const Row& run = by_seed.at(std::to_string(record.seed));
    EXPECT_EQ(run[0], ompl_planner_name(record.planner, record.checker)) << what;
    expect_real(run[2], record.time_s, what + ": time");
    EXPECT_EQ(run[3], record.solved ? "1" : "0") << what;
    EXPECT_EQ(run[4], std::to_string(enum_value.at(record.status))) << what;
    const bool has_path = record.status == "exact" || record.status == "approximate";
    EXPECT_EQ(run[5], has_path ? (record.status == "approximate" ? "1" : "0") : "NULL") << what;
    EXPECT_EQ(run[6], record.path_check == "pass"   ? "1"
                      : record.path_check == "fail" ? "0"
                                                    : "NULL")
        << what;
    expect_real(run[7], record.length, what + ": solution length");
    expect_real(run[8], record.simplified_length, what + ": simplified solution length");
    expect_real(run[9], record.simplify_time_s, what + ": simplification time");
    expect_real(run[10], record.memory_mb, what + ": memory");
    EXPECT_EQ(run[11], record.graph_states < 0 ? "NULL" : std::to_string(record.graph_states))
        << what;
    EXPECT_EQ(run[12], record.checks < 0 ? "NULL" : std::to_string(record.checks)) << what;
    EXPECT_EQ(run[13], record.note.empty() ? "NULL" : record.note) << what;
    EXPECT_EQ(run[14], "1") << what;
  }
}

TEST(OmplLog, HostileNamesAreMadeSafeForTheFormat) {
  OmplLogExperiment experiment = piano_experiment();
  experiment.name = "regression: piano\nExperiment evil; |>>>\xC2\xA0x";
  experiment.host = "my host";
  experiment.date = "2024-05-01 13:45\n07";
  experiment.setup = "scene: a\n|>>> not the end\r\n<<<|\nlast line without a newline";
  experiment.cpu_info = "";
  BenchRecord record = planning_record("ompl-prm", "cpu", 0, "exact");
  record.note = "fell back; to cpu\n|>>>; ";
  std::ostringstream text;
  write_ompl_log(text, experiment, {record});
  const std::vector<std::string> lines = lines_of(text.str());

  const std::vector<std::string> head = {
      "OMPL version " + ompl_version(),
      "Experiment regression:_piano\\nExperiment_evil;_|>>>_x",
      "0 experiment properties",
      "Running on my_host",
      "Starting at 2024-05-01 13:45\\n07",
      "<<<|",
      "scene: a",
      " |>>> not the end\\r",
      "<<<|",
      "last line without a newline",
      "|>>>",
      "<<<|",
      "|>>>",
      "1001 is the random seed",
      "5 seconds per run",
      "4096 MB per run",
      "3 runs per planner",
      "42.5 seconds spent to collect the data",
      "1 enum type",
  };
  ASSERT_GT(lines.size(), head.size());
  for (std::size_t i = 0; i < head.size(); ++i) EXPECT_EQ(lines[i], head[i]) << "line " << i + 1;
  EXPECT_EQ(lines[head.size()].rfind("status|Unknown status|Invalid start|", 0), 0u)
      << lines[head.size()];

  // The planner: its name, 3 common properties, 14 run properties, 1 run, ".".
  const std::size_t planner = head.size() + 2;
  EXPECT_EQ(lines[planner - 1], "1 planners");
  EXPECT_EQ(lines[planner], "geometric_PRM_cpu");
  EXPECT_EQ(lines[planner + 1], "3 common properties");
  EXPECT_EQ(lines[planner + 5], "14 properties for each run");
  EXPECT_EQ(lines[planner + 12], "note STRING");
  EXPECT_EQ(lines[planner + 20], "1 runs");
  const std::string& values = lines[planner + 21];
  int fields = 0;
  for (std::size_t at = values.find("; "); at != std::string::npos; at = values.find("; ", at + 2))
    ++fields;
  EXPECT_EQ(fields, 14) << values;
  EXPECT_NE(values.find("fell back, to cpu\\n|>>>, ; "), std::string::npos) << values;
  EXPECT_EQ(lines[planner + 22], ".");
  EXPECT_EQ(lines.size(), planner + 23);
}

TEST(OmplLog, HostileNamesReadBackThroughOmplBenchmarkStatistics) {
  ScratchFolder folder;
  OmplLogExperiment experiment = piano_experiment();
  experiment.name = "regression: piano\n2 planners";
  experiment.setup = "scene: a\n|>>>\nlast";
  BenchRecord record = planning_record("ours-prm", "fcl", 0, "exact");
  record.note = "a; b\nc";
  const std::string log = folder.path() + "/hostile.log";
  write_ompl_log_file(log, experiment, {record});
  const std::string database = load_into_database(folder, log);
  ASSERT_FALSE(database.empty());
  const std::vector<Row> experiments =
      query(folder, database, "SELECT name, setup FROM experiments");
  ASSERT_EQ(experiments.size(), 1u);
  EXPECT_EQ(experiments[0][0], "regression:_piano\\n2_planners");
  EXPECT_EQ(experiments[0][1], "scene: a\n |>>>\nlast\n");
  const std::vector<Row> runs = query(folder, database, "SELECT note, solved, seed FROM runs");
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0], (Row{"a, b\\nc", "1", std::to_string(record.seed)}));
}

TEST(OmplLog, BadRecordsAreRefusedBeforeAnythingIsWritten) {
  const auto refusal = [](const BenchRecord& record) -> std::string {
    std::ostringstream text;
    try {
      write_ompl_log(text, piano_experiment(),
                     {planning_record("ompl-prm", "fcl", 0, "exact"), record});
    } catch (const std::invalid_argument& error) {
      EXPECT_EQ(text.str(), "") << "written before the refusal";
      return error.what();
    }
    return "not refused";
  };
  BenchRecord status = planning_record("ompl-prm", "fcl", 1, "exact");
  status.status = "done";
  EXPECT_NE(refusal(status).find("run 1: the status 'done'"), std::string::npos) << refusal(status);
  BenchRecord planner = planning_record("ompl-prm", "fcl", 1, "exact");
  planner.planner = "ompl-kpiece";
  EXPECT_NE(refusal(planner).find("planner 'ompl-kpiece'"), std::string::npos) << refusal(planner);
  BenchRecord checker = planning_record("ompl-prm", "gpu-packet", 1, "exact");
  EXPECT_NE(refusal(checker).find("the checker 'gpu-packet'"), std::string::npos)
      << refusal(checker);
  BenchRecord check = planning_record("ompl-prm", "fcl", 1, "exact");
  check.path_check = "ok";
  EXPECT_NE(refusal(check).find("the path check 'ok'"), std::string::npos) << refusal(check);
  BenchRecord contradiction = planning_record("ompl-prm", "fcl", 1, "timeout");
  contradiction.solved = true;
  EXPECT_NE(refusal(contradiction).find("solved is true but the status is 'timeout'"),
            std::string::npos)
      << refusal(contradiction);

  OmplLogExperiment no_limit = piano_experiment();
  no_limit.time_limit_s = kNotMeasured;
  std::ostringstream text;
  EXPECT_THROW(write_ompl_log(text, no_limit, {}), std::invalid_argument);
  EXPECT_EQ(text.str(), "");
}

TEST(OmplLog, PlannerNamesFollowOmpl) {
  EXPECT_EQ(ompl_planner_name("ompl-rrtconnect", "fcl"), "geometric_RRTConnect_fcl");
  EXPECT_EQ(ompl_planner_name("ompl-prm", "cpu"), "geometric_PRM_cpu");
  EXPECT_EQ(ompl_planner_name("ompl-lazyprm", "gpu"), "geometric_LazyPRM_gpu");
  EXPECT_EQ(ompl_planner_name("ours-lazyprm", "gpu"), "gplanner_LazyPRM_gpu");
  EXPECT_EQ(ompl_planner_name("ours-prm", "cpu"), "gplanner_PRM_cpu");
  EXPECT_THROW(ompl_planner_name("collision-queries", "gpu"), std::invalid_argument);
}

TEST(OmplLog, MachineAndDate) {
  EXPECT_FALSE(ompl_host_name().empty());
  EXPECT_TRUE(std::regex_match(local_date_time(), std::regex(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d)")))
      << local_date_time();
}

}  // namespace
}  // namespace gplan

namespace gplan {
namespace {

// The plugin's sampled motion validator (@gpu-sampled, @cpu-sampled) is a checker of its
// own in the log, described as sampled.
TEST(OmplLog, SampledPluginCheckersAreLogged) {
  for (const char* checker : {"gpu-sampled", "cpu-sampled"}) {
    std::ostringstream text;
    write_ompl_log(text, piano_experiment(),
                   {planning_record("ompl-rrtconnect", checker, 0, "exact")});
    EXPECT_NE(text.str().find("motions sampled"), std::string::npos) << checker;
  }
}

}  // namespace
}  // namespace gplan
