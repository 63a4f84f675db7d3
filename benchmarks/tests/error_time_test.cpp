// The error-against-time study (`gplan bench` kind error-time, benchmarks/harness/error_time_*):
// CI's configuration through the real gplan writes its CSV, table and plots with numbers
// that behave (missed edges do not grow as the resolution gets finer, certified edges
// and the cpu and fcl states miss none, counts add up); the ground truth decides a
// motion through a thin wall and one through its window; configurations are refused
// naming the file, line and key. GPU cases (names contain "Gpu") skip without a device.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "harness/bench_config.h"
#include "harness/bench_plots.h"
#include "harness/error_time_truth.h"
#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "bench_test_support.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::CommandResult;
using gplanner::testing::project_root;
using gplanner::testing::read_file;
using gplanner::testing::run_gplan_bench;
using gplanner::testing::ScratchFolder;
using gplanner::testing::shell_quoted;

std::string ci_config() { return project_root() + "/benchmarks/config/error_time_ci.yaml"; }
std::string thin_wall_file() {
  return project_root() + "/benchmarks/config/error_time_ci/thin_wall.yaml";
}

bool has_gpu() { return gplanner::query_gpu_device().available; }

// A row of results.csv by column name (the study writes no quoted fields for these
// scenes).
using Row = std::map<std::string, std::string>;

std::vector<Row> read_rows(const std::string& file) {
  std::istringstream text(read_file(file));
  std::vector<std::string> header;
  std::vector<Row> rows;
  for (std::string line; std::getline(text, line);) {
    const std::vector<std::string> fields = gplanner::testing::split_fields(line);
    if (header.empty()) {
      header = fields;
      continue;
    }
    EXPECT_EQ(fields.size(), header.size()) << line;
    Row row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(row);
  }
  return rows;
}

long long count(const Row& row, const std::string& column) { return std::stoll(row.at(column)); }

std::vector<Row> of_knob(const std::vector<Row>& rows, const std::string& knob,
                         const std::string& checker) {
  std::vector<Row> out;
  for (const Row& row : rows)
    if (row.at("knob") == knob && row.at("checker") == checker) out.push_back(row);
  return out;
}

TEST(GplanBenchErrorTime, CiConfigurationWritesItsCsvTableAndPlotsWithNumbersThatBehave) {
  const ScratchFolder folder;
  const std::string out = folder.path() + "/study";
  const CommandResult run = run_gplan_bench(ci_config() + " -o " + shell_quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // Progress while it runs.
  EXPECT_NE(run.output.find("thin_wall: ground truth (FCL in double"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("thin_wall edge-resolution 0.08 cpu:"), std::string::npos)
      << run.output;

  const std::vector<Row> rows = read_rows(out + "/results.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(read_file(out + "/results.csv").substr(0, 40),
            std::string("scene,knob,value,checker,time_s,missed,e"));
  // Every curve of cpu and fcl, every point of each: 2 precision, 2 delta (cpu), 5 + 5
  // edge resolutions, 2 + 2 certified steps, and planning: 2 + 3 points per checker.
  EXPECT_EQ(rows.size(), 2u + 2 + 10 + 4 + 10);
  for (const Row& row : rows) {
    SCOPED_TRACE(row.at("knob") + " " + row.at("value") + " " + row.at("checker"));
    EXPECT_EQ(row.at("scene"), "thin_wall");
    EXPECT_NE(row.at("checker").rfind("gpu", 0), 0u);  // no gpu here, never its name
    EXPECT_GT(std::stod(row.at("time_s")), 0);
    if (!row.at("runs").empty()) {  // planning: solved of runs, failing paths of solved
      EXPECT_EQ(count(row, "runs"), 2);
      EXPECT_EQ(count(row, "total"), 2);
      EXPECT_LE(count(row, "solved"), count(row, "runs"));
      EXPECT_LE(count(row, "path_fails") + count(row, "path_undecided"), count(row, "solved"));
      EXPECT_EQ(row.at("missed"), "");
    } else {  // states and edges: the errors within the decided ones
      EXPECT_GE(count(row, "missed"), 0);
      EXPECT_GE(count(row, "extra"), 0);
      EXPECT_LE(count(row, "missed") + count(row, "extra") + count(row, "undecided"),
                count(row, "total"));
      EXPECT_EQ(row.at("solved"), "");
    }
  }
  for (const std::string checker : {"cpu", "fcl"}) {
    SCOPED_TRACE(checker);
    // Missed edges do not grow as the resolution gets finer (the config lists it coarse
    // to fine), and the coarsest, 8 times the scene's, jumps over the 2 cm wall.
    const std::vector<Row> sampled = of_knob(rows, "edge-resolution", checker);
    ASSERT_EQ(sampled.size(), 5u);
    EXPECT_EQ(sampled[0].at("value"), "0.08");
    EXPECT_GT(count(sampled[0], "missed"), 0);
    for (std::size_t i = 1; i < sampled.size(); ++i)
      EXPECT_LE(count(sampled[i], "missed"), count(sampled[i - 1], "missed")) << i;
    EXPECT_EQ(count(sampled[0], "total"), 300);
    // Certified edges miss none.
    const std::vector<Row> certified = of_knob(rows, "certified-step", checker);
    ASSERT_EQ(certified.size(), 2u);
    for (const Row& row : certified) EXPECT_EQ(count(row, "missed"), 0);
    // States: the cpu backend and FCL miss none (the cpu's band may add extra ones).
    const std::vector<Row> states = of_knob(rows, "precision", checker);
    ASSERT_EQ(states.size(), 1u);
    EXPECT_EQ(count(states[0], "missed"), 0);
    EXPECT_EQ(count(states[0], "total"), 2000);
    EXPECT_EQ(states[0].at("value"), checker == "fcl" ? "double" : "float");
    // Plans with every edge-checks setting; certified paths never through the wall.
    const std::vector<Row> plans = of_knob(rows, "plan-edges", checker);
    ASSERT_EQ(plans.size(), 3u);
    for (const Row& row : plans)
      if (row.at("value") != "sampled") EXPECT_EQ(count(row, "path_fails"), 0) << row.at("value");
  }
  EXPECT_EQ(of_knob(rows, "precision", "fcl")[0].at("extra"), "0");  // the truth itself
  EXPECT_EQ(of_knob(rows, "delta", "cpu").size(), 2u);
  EXPECT_TRUE(of_knob(rows, "delta", "fcl").empty());  // FCL has no band

  // The table, the configuration as read, the plots (or a notice saying why not).
  const std::string table = read_file(out + "/results.md");
  EXPECT_NE(table.find("## thin_wall"), std::string::npos) << table;
  EXPECT_NE(table.find("| edge-resolution | 0.08 | cpu |"), std::string::npos) << table;
  EXPECT_EQ(read_file(out + "/config.yaml"), read_file(ci_config()));
  EXPECT_FALSE(fs::exists(out + "/results.partial.csv"));
  if (run.output.find("notice: no plots") == std::string::npos) {
    EXPECT_GT(fs::file_size(out + "/plots/thin_wall.png"), 1000u);
    EXPECT_GT(fs::file_size(out + "/plots/thin_wall.svg"), 1000u);
  } else {
    EXPECT_NE(run.output.find("python3-matplotlib"), std::string::npos) << run.output;
  }
}

TEST(GplanBenchErrorTime, PlotsOfOneCsvAreTheSameWhenDrawnTwice) {
  const ScratchFolder folder;
  const std::string out = folder.path() + "/study";
  const CommandResult run =
      run_gplan_bench(ci_config() + " -o " + shell_quoted(out) + " --no-plots");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::string notice;
  if (!draw_error_time_plots(out + "/results.csv", folder.path() + "/one", &notice))
    GTEST_SKIP() << notice;
  ASSERT_TRUE(draw_error_time_plots(out + "/results.csv", folder.path() + "/two", &notice))
      << notice;
  for (const char* file : {"/thin_wall.png", "/thin_wall.svg"}) {
    const std::string one = read_file(folder.path() + "/one" + file);
    EXPECT_GT(one.size(), 1000u) << file;
    EXPECT_EQ(one, read_file(folder.path() + "/two" + file)) << file;
  }
  // A CSV that is not the study's: no figure, a notice with the script's exit code.
  const std::string bad = folder.write("bad.csv", "scene,knob\nx,y\n");
  EXPECT_FALSE(draw_error_time_plots(bad, folder.path() + "/three", &notice));
  EXPECT_NE(notice.find("exited with code 2"), std::string::npos) << notice;
  EXPECT_FALSE(fs::exists(folder.path() + "/three/x.png"));
}

TEST(GplanBenchErrorTime, RefusesAFolderWithFilesAndOptionsOfOtherKinds) {
  const ScratchFolder folder;
  folder.write("kept.txt", "mine\n");
  const CommandResult full =
      run_gplan_bench(ci_config() + " -o " + shell_quoted(folder.path()));
  EXPECT_EQ(full.exit_code, 2) << full.output;
  EXPECT_NE(full.output.find("has files in it"), std::string::npos) << full.output;
  EXPECT_EQ(read_file(folder.path() + "/kept.txt"), "mine\n");
  EXPECT_FALSE(fs::exists(folder.path() + "/results.csv"));

  const CommandResult baseline =
      run_gplan_bench(ci_config() + " -o " + shell_quoted(folder.path() + "/new") +
                " --baseline " + ci_config());
  EXPECT_EQ(baseline.exit_code, 2) << baseline.output;
  EXPECT_NE(baseline.output.find("--baseline does not apply to the error-time study"),
            std::string::npos)
      << baseline.output;
  EXPECT_FALSE(fs::exists(folder.path() + "/new"));
}

TEST(GplanBenchErrorTime, GpuNamedWhereNoneCanBeUsedLeavesItsCurvesOutWithANotice) {
  if (has_gpu()) GTEST_SKIP() << "a GPU is here: its curves run (ErrorTimeGpu covers them)";
  const ScratchFolder folder;
  const std::string config = folder.write(
      "gpu.yaml", "kind: error-time\nscenes: [" + thin_wall_file() +
                      "]\ncheckers: [gpu, cpu]\nstates: 200\nedges: 40\nroadmap_milestones: 60\n"
                      "edge_resolutions: [1]\ncertified_steps: [0.02]\ntruth_step: 0.002\n"
                      "deltas: [1.0e-5]\nplan_milestones: [100]\nruns: 1\nrepeat: 1\n");
  const std::string out = folder.path() + "/out";
  const CommandResult run =
      run_gplan_bench(config + " -o " + shell_quoted(out) + " --no-plots");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("the gpu curves"), std::string::npos) << run.output;
  const std::vector<Row> rows = read_rows(out + "/results.csv");
  ASSERT_FALSE(rows.empty());
  for (const Row& row : rows) EXPECT_EQ(row.at("checker"), "cpu");
  EXPECT_NE(read_file(out + "/results.md").find("Left out:"), std::string::npos);
}

TEST(ErrorTimeGpu, TraversalAndPrecisionCurvesRunOnTheGpu) {
  if (!has_gpu()) GTEST_SKIP() << "no GPU";
  const ScratchFolder folder;
  const std::string config = folder.write(
      "gpu.yaml", "kind: error-time\nscenes: [" + thin_wall_file() +
                      "]\ncheckers: [gpu]\nstates: 2000\nedges: 100\nroadmap_milestones: 100\n"
                      "edge_resolutions: [8, 1]\ncertified_steps: [0.02]\ntruth_step: 0.002\n"
                      "deltas: [1.0e-5]\nplan_milestones: [100]\nruns: 1\nrepeat: 1\n");
  const std::string out = folder.path() + "/out";
  const CommandResult run =
      run_gplan_bench(config + " -o " + shell_quoted(out) + " --no-plots");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<Row> rows = read_rows(out + "/results.csv");
  for (const std::string checker : {"gpu-basic", "gpu-packet", "gpu-balanced"}) {
    const std::vector<Row> traversal = of_knob(rows, "traversal", checker);
    ASSERT_EQ(traversal.size(), 1u) << checker;
    EXPECT_EQ(count(traversal[0], "missed"), 0) << checker;
  }
  ASSERT_EQ(of_knob(rows, "precision", "gpu").size(), 1u);
  EXPECT_EQ(count(of_knob(rows, "precision", "gpu")[0], "missed"), 0);
  ASSERT_EQ(of_knob(rows, "certified-step", "gpu").size(), 1u);
  EXPECT_EQ(count(of_knob(rows, "certified-step", "gpu")[0], "missed"), 0);
}

// The ground truth on the thin wall: through the wall colliding, through the window
// free; and a sampled check coarse enough jumps over the wall that the truth catches.
TEST(ErrorTimeTruth, DecidesAMotionThroughTheThinWallAndOneThroughItsWindow) {
  const gplanner::Scene scene = gplanner::load_scene(thin_wall_file());
  GroundTruth truth(scene, 0.005);
  ASSERT_EQ(scene.space.width(), 7);
  // x y z, quaternion w x y z: level, at y = -1.2 (the wall) and y = 0 (the window).
  const std::vector<float> from = {-0.5f, -1.2f, 1.0f, 1, 0, 0, 0, -0.5f, 0, 1.0f, 1, 0, 0, 0};
  const std::vector<float> to = {0.5f, -1.2f, 1.0f, 1, 0, 0, 0, 0.5f, 0, 1.0f, 1, 0, 0, 0};
  const std::vector<MotionTruth> verdicts = truth.motions(from.data(), to.data(), 2);
  ASSERT_EQ(verdicts.size(), 2u);
  EXPECT_EQ(verdicts[0], MotionTruth::kColliding);
  EXPECT_EQ(verdicts[1], MotionTruth::kFree);
  EXPECT_EQ(truth.states(from.data(), 2), (std::vector<std::uint8_t>{0, 0}));
  // A path along the free motion passes; one through the wall fails.
  EXPECT_EQ(truth.path({from.begin() + 7, from.end()}), "pass");  // one free waypoint
  std::vector<float> window_path(from.begin() + 7, from.end());
  window_path.insert(window_path.end(), to.begin() + 7, to.end());
  EXPECT_EQ(truth.path(window_path), "pass");
  std::vector<float> wall_path(from.begin(), from.begin() + 7);
  wall_path.insert(wall_path.end(), to.begin(), to.begin() + 7);
  EXPECT_EQ(truth.path(wall_path), "fail");
  // The sampled check with one segment (the ends only, which are free) misses the wall.
  gplanner::LocalPlannerOptions coarse;
  coarse.resolution_fraction = 1;
  gplanner::LocalPlanner sampled(scene, truth.checker(), coarse);
  std::uint8_t invalid = 1;
  ASSERT_TRUE(sampled.check_motions(from.data(), to.data(), 1, &invalid));
  EXPECT_EQ(invalid, 0);
}

void expect_refused(const std::string& text, const std::string& where_and_problem) {
  const ScratchFolder folder;
  const std::string file = folder.write("bench.yaml", text);
  try {
    load_bench_config(file);
    ADD_FAILURE() << "accepted:\n" << text;
  } catch (const gplanner::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file + ":" + where_and_problem), std::string::npos)
        << e.what();
  }
}

TEST(ErrorTimeConfig, ReadsEveryKeyAndRefusesMistakesNamingTheLineAndKey) {
  const std::string head = "kind: error-time\nscenes: [" + thin_wall_file() + "]\n";
  {
    const ScratchFolder folder;
    const BenchConfig c = load_bench_config(folder.write(
        "bench.yaml", head + "checkers: [fcl, cpu]\nstates: 10\nedges: 20\nroadmap_milestones: 30\n"
                             "edge_resolutions: [2, 0.5]\ncertified_steps: [0.1]\n"
                             "truth_step: 0.01\ndeltas: [2.0e-6]\nplan_milestones: [40, 50]\n"
                             "runs: 3\ntime_limit: 4\nrepeat: 5\nseed: 6\n"));
    EXPECT_EQ(c.kind, "error-time");
    EXPECT_EQ(c.error_time.checkers, (std::vector<std::string>{"fcl", "cpu"}));
    EXPECT_EQ(c.error_time.states, 10u);
    EXPECT_EQ(c.error_time.edges, 20u);
    EXPECT_EQ(c.error_time.roadmap_milestones, 30u);
    EXPECT_EQ(c.error_time.edge_resolutions, (std::vector<double>{2, 0.5}));
    EXPECT_EQ(c.error_time.certified_steps, (std::vector<double>{0.1}));
    EXPECT_DOUBLE_EQ(c.error_time.truth_step, 0.01);
    EXPECT_EQ(c.error_time.deltas, (std::vector<double>{2e-6}));
    EXPECT_EQ(c.error_time.plan_milestones, (std::vector<double>{40, 50}));
    EXPECT_EQ(c.error_time.runs, 3);
    EXPECT_DOUBLE_EQ(c.error_time.time_limit_s, 4);
    EXPECT_EQ(c.error_time.repeat, 5);
    EXPECT_EQ(c.seed, 6u);
  }
  expect_refused(head, "1: checkers: missing; add it");  // the map's line
  expect_refused(head + "checkers: [gpu, cuda]\n",
                 "3: checkers[1]: 'cuda' is not one of gpu, cpu, fcl");
  expect_refused(head + "checkers: [cpu, cpu]\n", "3: checkers[1]: 'cpu' is listed twice");
  expect_refused(head + "checkers: [cpu]\ndeltas: [2.0e-5]\n",
                 "4: deltas[0]: expected a number above 0");
  expect_refused(head + "checkers: [cpu]\ncertified_steps: [0.01]\ntruth_step: 0.02\n",
                 "5: truth_step: the ground truth's step 0.02 must be at most the smallest");
  expect_refused(head + "checkers: [cpu]\nedge_resolutions: []\n",
                 "4: edge_resolutions: expected a list");
  expect_refused(head + "checkers: [cpu]\nplan_milestones: [100.5]\n",
                 "4: plan_milestones[0]: expected a whole number");
  expect_refused(head + "checkers: [cpu]\nstates: 0\n",
                 "4: states: expected a whole number from 1");
  expect_refused(head + "checkers: [cpu]\ntables: [local-planning]\n",
                 "4: tables: does not apply to kind: error-time");
  expect_refused(head + "checkers: [cpu]\ntolerances: {time_ratio: 2}\n",
                 "4: tolerances: does not apply to kind: error-time");
  expect_refused("kind: planning\nscenes: [" + thin_wall_file() +
                     "]\nplanners: [ours-prm@cpu]\ndeltas: [1.0e-6]\n",
                 "4: deltas: does not apply to kind: planning");
  expect_refused("kind: error\nscenes: [" + thin_wall_file() + "]\n",
                 "1: kind: 'error' is not one of planning, queries, error-time");
}

}  // namespace
}  // namespace gplan
