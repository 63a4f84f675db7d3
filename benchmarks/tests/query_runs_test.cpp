// The seed's query tables as `gplan bench` runs them (benchmarks/harness/query_runs): records
// and their fields, the same workload for every checker (cpu and fcl agree within the
// tolerance band: the cpu backend may find extra collisions, never fewer), and the
// names it refuses. GPU cases (names contain "Gpu") skip where there is no device.

#include "harness/query_runs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplan {
namespace {

const gplanner::Scene& piano() {
  static const gplanner::Scene scene =
      gplanner::load_scene(gplanner::testing::project_root() + "/scenes/piano.yaml");
  return scene;
}

QueryTableOptions small_options() {
  QueryTableOptions options;
  options.queries = 2000;
  options.milestones = 100;
  options.neighbors = 10;
  options.repeat = 2;
  options.seed = 7;
  return options;
}

std::vector<BenchRecord> run_group(const std::string& table, const std::string& checker,
                                   const QueryTableOptions& options = small_options()) {
  std::vector<BenchRecord> records;
  run_query_group(piano(), "tables", "piano", table, checker, options,
                  [&](const BenchRecord& record) { records.push_back(record); }, [] { return false; });
  return records;
}

// Every record of a group describes the same batch: the same work and verdicts.
void expect_one_batch(const std::vector<BenchRecord>& records, const std::string& table,
                      const std::string& checker, const QueryTableOptions& options) {
  ASSERT_EQ(records.size(), static_cast<std::size_t>(options.repeat));
  for (std::size_t r = 0; r < records.size(); ++r) {
    const BenchRecord& record = records[r];
    EXPECT_EQ(record.experiment, "tables");
    EXPECT_EQ(record.scene, "piano");
    EXPECT_EQ(record.planner, table);
    EXPECT_EQ(record.checker, checker);
    EXPECT_EQ(record.run, static_cast<int>(r));
    EXPECT_EQ(record.seed, options.seed);
    EXPECT_EQ(record.status, "measured");
    EXPECT_FALSE(record.solved);
    EXPECT_TRUE(std::isfinite(record.time_s));
    EXPECT_GT(record.time_s, 0.0);
    EXPECT_GT(record.work, 0);
    EXPECT_GE(record.collisions, 0);
    EXPECT_LE(record.collisions, record.work);
    EXPECT_EQ(record.work, records[0].work);
    EXPECT_EQ(record.collisions, records[0].collisions);
    EXPECT_EQ(record.note, "");
    EXPECT_EQ(record.checks, -1);
    EXPECT_EQ(record.path_check, "");
  }
}

TEST(QueryRuns, CollisionQueriesRecordOneBatchPerTimedCall) {
  const QueryTableOptions options = small_options();
  const std::vector<BenchRecord> records = run_group("collision-queries", "cpu", options);
  expect_one_batch(records, "collision-queries", "cpu", options);
  EXPECT_EQ(records[0].work, 2000);
  // The piano's rooms leave part of the space free and part not.
  EXPECT_GT(records[0].collisions, 0);
  EXPECT_LT(records[0].collisions, 2000);
}

TEST(QueryRuns, CollisionQueriesAreTheBatchGplanCheckDraws) {
  // gplan check --seed S: uniform rows from std::mt19937_64(S), in order.
  const QueryTableOptions options = small_options();
  const gplanner::Scene& scene = piano();
  const std::size_t width = scene.space.width();
  std::vector<float> q(options.queries * width);
  std::mt19937_64 rng(options.seed);
  for (std::size_t i = 0; i < options.queries; ++i) scene.space.sample_uniform(&rng, &q[i * width]);
  std::vector<std::uint8_t> verdicts(options.queries);
  gplanner::FclChecker fcl(scene);
  fcl.check(q.data(), options.queries, verdicts.data());
  long long collisions = 0;
  for (const std::uint8_t v : verdicts) collisions += v != 0;

  const std::vector<BenchRecord> records = run_group("collision-queries", "fcl", options);
  expect_one_batch(records, "collision-queries", "fcl", options);
  EXPECT_EQ(records[0].collisions, collisions);
}

TEST(QueryRuns, CollisionQueriesCpuFindsFclsCollisionsAndFewExtra) {
  const QueryTableOptions options = small_options();
  const std::vector<BenchRecord> cpu = run_group("collision-queries", "cpu", options);
  const std::vector<BenchRecord> fcl = run_group("collision-queries", "fcl", options);
  ASSERT_FALSE(cpu.empty());
  ASSERT_FALSE(fcl.empty());
  EXPECT_EQ(cpu[0].work, fcl[0].work);
  // The band: the cpu backend never misses a collision FCL finds and reports extra ones
  // only within delta of contact, which few uniform samples come.
  EXPECT_GE(cpu[0].collisions, fcl[0].collisions);
  EXPECT_LE(cpu[0].collisions - fcl[0].collisions, cpu[0].work / 100);
}

TEST(QueryRuns, LocalPlanningChecksTheSameEdgesOnEveryChecker) {
  const QueryTableOptions options = small_options();
  const std::vector<BenchRecord> cpu = run_group("local-planning", "cpu", options);
  const std::vector<BenchRecord> fcl = run_group("local-planning", "fcl", options);
  expect_one_batch(cpu, "local-planning", "cpu", options);
  expect_one_batch(fcl, "local-planning", "fcl", options);
  // k nearest of each milestone, undirected edges once: between n k / 2 and n k.
  const long long n = options.milestones, k = options.neighbors;
  EXPECT_GE(cpu[0].work, n * k / 2);
  EXPECT_LE(cpu[0].work, n * k);
  EXPECT_EQ(cpu[0].work, fcl[0].work);
  // Walls between the rooms: some edges cross them, others are free.
  EXPECT_GT(fcl[0].collisions, 0);
  EXPECT_LT(cpu[0].collisions, cpu[0].work);
  EXPECT_GE(cpu[0].collisions, fcl[0].collisions);
  EXPECT_LE(cpu[0].collisions - fcl[0].collisions, cpu[0].work / 100);
}

TEST(QueryRuns, TheWorkloadFollowsTheSeed) {
  QueryTableOptions options = small_options();
  options.repeat = 1;
  const std::vector<BenchRecord> first = run_group("local-planning", "cpu", options);
  const std::vector<BenchRecord> again = run_group("local-planning", "cpu", options);
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(first[0].work, again[0].work);
  EXPECT_EQ(first[0].collisions, again[0].collisions);
  options.seed = 8;
  const std::vector<BenchRecord> other = run_group("local-planning", "cpu", options);
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(other[0].seed, 8u);
  EXPECT_TRUE(other[0].work != first[0].work || other[0].collisions != first[0].collisions)
      << "seeds 7 and 8 gave the same roadmap";
}

// The exception's message for `table` and `checker`, empty when none was thrown; no
// record may come before it.
std::string refusal(const std::string& table, const std::string& checker,
                    const QueryTableOptions& options = small_options()) {
  std::size_t records = 0;
  try {
    run_query_group(piano(), "tables", "piano", table, checker, options,
                    [&](const BenchRecord&) { ++records; }, [] { return false; });
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(records, 0u);
    return e.what();
  }
  return "";
}

TEST(QueryRuns, RefusesAnUnknownCheckerNamingTheKnownOnes) {
  const std::string message = refusal("collision-queries", "gpu-fast");
  EXPECT_NE(message.find("'gpu-fast'"), std::string::npos) << message;
  for (const std::string& name : query_table_checkers())
    EXPECT_NE(message.find(name), std::string::npos) << message;
  EXPECT_NE(refusal("local-planning", "gpu"), "");
  EXPECT_NE(refusal("local-planning", ""), "");
}

TEST(QueryRuns, RefusesAnUnknownTableNamingTheKnownOnes) {
  const std::string message = refusal("planning", "cpu");
  EXPECT_NE(message.find("'planning'"), std::string::npos) << message;
  EXPECT_NE(message.find("collision-queries"), std::string::npos) << message;
  EXPECT_NE(message.find("local-planning"), std::string::npos) << message;
}

TEST(QueryRuns, RefusesOptionsOutOfRange) {
  QueryTableOptions options = small_options();
  options.repeat = 0;
  EXPECT_NE(refusal("collision-queries", "cpu", options).find("repeat"), std::string::npos);
  options = small_options();
  options.queries = 0;
  EXPECT_NE(refusal("collision-queries", "cpu", options).find("queries"), std::string::npos);
  options = small_options();
  options.milestones = 1;
  EXPECT_NE(refusal("local-planning", "cpu", options).find("milestones"), std::string::npos);
  options = small_options();
  options.neighbors = 0;
  EXPECT_NE(refusal("local-planning", "cpu", options).find("neighbors"), std::string::npos);
}

TEST(QueryRuns, CheckerNamesAreTheSeedsTraversalsThenCpuAndFcl) {
  EXPECT_EQ(query_table_checkers(),
            (std::vector<std::string>{"gpu-basic", "gpu-packet", "gpu-balanced", "cpu", "fcl"}));
  EXPECT_EQ(query_tables(), (std::vector<std::string>{"collision-queries", "local-planning"}));
}

TEST(QueryRuns, RefusesAGpuCheckerWithoutADeviceRatherThanTimingTheCpuUnderItsName) {
  const gplanner::GpuDevice device = gplanner::query_gpu_device();
  if (device.available) GTEST_SKIP() << "a GPU is there: no fallback to see";
  QueryTableOptions options = small_options();
  options.repeat = 1;
  try {
    run_group("collision-queries", "gpu-packet", options);
    FAIL() << "the cpu backend was timed as gpu-packet";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gpu-packet is left out"), std::string::npos) << e.what();
  }
}

class QueryRunsGpu : public ::testing::TestWithParam<std::string> {};

TEST_P(QueryRunsGpu, AnswersAsTheCpuBackendWithinTheBand) {
  REQUIRE_GPU();
  const QueryTableOptions options = small_options();
  for (const std::string table : {"collision-queries", "local-planning"}) {
    const std::vector<BenchRecord> gpu = run_group(table, GetParam(), options);
    const std::vector<BenchRecord> fcl = run_group(table, "fcl", options);
    expect_one_batch(gpu, table, GetParam(), options);
    ASSERT_FALSE(fcl.empty());
    EXPECT_EQ(gpu[0].work, fcl[0].work) << table;
    EXPECT_GE(gpu[0].collisions, fcl[0].collisions) << table;
    EXPECT_LE(gpu[0].collisions - fcl[0].collisions, gpu[0].work / 100) << table;
  }
}

INSTANTIATE_TEST_SUITE_P(Traversals, QueryRunsGpu,
                         ::testing::Values("gpu-basic", "gpu-packet", "gpu-balanced"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           name.replace(name.find('-'), 1, "_");
                           return name;
                         });

}  // namespace
}  // namespace gplan
