// The OMPL benchmark example end to end: OMPL's planners and ours inside
// ompl::tools::Benchmark on a shipped scene (cpu backend), the log read by OMPL's own
// ompl_benchmark_statistics into SQLite, and the runs table queried.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "test_support.h"

namespace gplanner {
namespace {

struct Output {
  int status = -1;
  std::string text;
};

Output run(const std::string& command) {
  Output out;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return out;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = fread(buffer, 1, sizeof(buffer), pipe)) > 0) out.text.append(buffer, got);
  const int status = pclose(pipe);
  out.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

TEST(OmplBenchmark, LogReadByOmplBenchmarkStatisticsIntoSqlite) {
  if (run("command -v ompl_benchmark_statistics").status != 0)
    GTEST_SKIP() << "ompl_benchmark_statistics (Debian package ompl-demos) is not installed";
  testing::ScratchFolder scratch;
  const std::string log = scratch.path() + "/bench.log", db = scratch.path() + "/bench.db";
  // In the scratch folder: OMPL's benchmark writes a console log where it runs.
  const Output bench =
      run("cd '" + scratch.path() + "' && '" + std::string(GPLANNER_OMPL_BENCHMARK_EXECUTABLE) +
          "' '" + testing::project_root() + "/scenes/pr2_base_arm.yaml' --backend cpu " +
          "--runs 1 --time-limit 5 --seed 1 --log '" + log + "'");
  ASSERT_EQ(bench.status, 0) << bench.text;
  ASSERT_TRUE(std::filesystem::exists(log)) << bench.text;
  const Output stats = run("ompl_benchmark_statistics '" + log + "' -d '" + db + "'");
  ASSERT_EQ(stats.status, 0) << stats.text;
  // One line per run: planner name, time, solved, solution length, graph states and
  // valid segment fraction.
  const Output query =
      run("python3 -c \"import sqlite3; c = sqlite3.connect('" + db +
          "'); [print('|'.join(str(v) for v in r)) for r in c.execute('select p.name, r.time, "
          "r.solved, r.solution_length, r.graph_states, r.valid_segment_fraction from runs r join "
          "plannerConfigs p on r.plannerid = p.id')]\"");
  ASSERT_EQ(query.status, 0) << query.text;
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream lines(query.text);
  for (std::string line; std::getline(lines, line);) {
    const std::vector<std::string> fields = testing::split_fields(line, '|');
    ASSERT_EQ(fields.size(), 6u) << line;
    rows[fields[0]] = fields;
  }
  for (const char* planner : {"geometric_RRTConnect", "geometric_PRM", "geometric_LazyPRM",
                              "geometric_gplanner PRM", "geometric_gplanner LazyPRM"}) {
    ASSERT_EQ(rows.count(planner), 1u) << planner << "\n" << query.text;
  }
  // Our lazy PRM and OMPL's RRTConnect solve the scene within the limit.
  for (const char* planner : {"geometric_gplanner LazyPRM", "geometric_RRTConnect"}) {
    const std::vector<std::string>& r = rows[planner];
    EXPECT_EQ(r[2], "1") << planner;
    EXPECT_GT(std::stod(r[1]), 0.0) << planner;
    EXPECT_LT(std::stod(r[1]), 10.0) << planner;
    EXPECT_GT(std::stod(r[3]), 0.0) << planner;  // solution length
    EXPECT_GT(std::stoi(r[4]), 0) << planner;    // graph states
  }
  // OMPL's planner checked its motions with our motion validator, ours their edges and
  // counted them there: some were valid.
  EXPECT_GT(std::stod(rows["geometric_RRTConnect"][5]), 0.0);
  EXPECT_GT(std::stod(rows["geometric_gplanner LazyPRM"][5]), 0.0);
  // Our planners' declared parameters are in the log.
  const Output settings =
      run("python3 -c \"import sqlite3; c = sqlite3.connect('" + db +
          "'); [print(r[1]) for r in c.execute('select name, settings from plannerConfigs') if "
          "r[0] == 'geometric_gplanner LazyPRM']\"");
  ASSERT_EQ(settings.status, 0) << settings.text;
  for (const char* param : {"milestones", "max_nearest_neighbors", "lazy_batch_paths", "seed"})
    EXPECT_NE(settings.text.find(param), std::string::npos) << param << "\n" << settings.text;
}

}  // namespace
}  // namespace gplanner
