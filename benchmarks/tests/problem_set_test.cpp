// gplan-bench on a MotionBenchMaker problem set (harness/motionbenchmaker): every problem
// a scene of MoveIt files, its records under its scenario; a problem whose start collides
// counted invalid (solved / valid / total), not an abort; and the real Panda set's first
// problem of every scenario, planned by our lazy PRM (its paths certified: none fails the
// FCL re-check).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "bench_test_support.h"
#include "harness/bench_record.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::CommandResult;
using gplanner::testing::read_file;
using gplanner::testing::run_gplan_bench;
using gplanner::testing::ScratchFolder;
using gplanner::testing::shell_quoted;

const char* const kArmUrdf = R"(<robot name="arm">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></collision></link>
  <link name="lower"><collision><origin xyz="0 0 0.15"/><geometry><box size="0.04 0.04 0.3"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>
)";

const char* const kArmSrdf = R"(<?xml version="1.0"?>
<robot name="arm"><group name="arm"><chain base_link="base" tip_link="lower"/></group></robot>
)";

// A box beside the arm, at x = 0.4 (or, `at_start`, on its base: start and goal collide).
std::string planning_scene(bool at_start) {
  return std::string(
             "world:\n  collision_objects:\n    - id: block\n      primitives: [{type: box, "
             "dimensions: [0.1, 0.1, 0.1]}]\n      primitive_poses: [{position: [") +
         (at_start ? "0, 0, 0" : "0.4, 0, 0.2") + "], orientation: [0, 0, 0, 1]}]\n";
}

const char* const kRequest = R"(group_name: arm
start_state: {joint_state: {name: [shoulder, elbow], position: [-1, 0.5]}}
goal_constraints:
  - joint_constraints:
      - {joint_name: shoulder, position: 1}
      - {joint_name: elbow, position: -0.5}
)";

// Two scenarios of two problems each, "front"'s second with its start in collision; the
// configuration's path.
std::string write_problem_set(const ScratchFolder& folder) {
  folder.write("robot/arm.urdf", kArmUrdf);
  folder.write("robot/arm.srdf", kArmSrdf);
  for (const char* scenario : {"beside", "front"}) {
    const std::string dir = std::string("problems/") + scenario + "/";
    folder.write(dir + "scene0001.yaml", planning_scene(false));
    folder.write(dir + "request0001.yaml", kRequest);
    folder.write(dir + "scene0002.yaml", planning_scene(std::string(scenario) == "front"));
    folder.write(dir + "request0002.yaml", kRequest);
  }
  return folder.write(
      "set.yaml",
      "name: set\nkind: planning\nmotionbenchmaker:\n  problems: problems\n  robot: {urdf: "
      "robot/arm.urdf, srdf: robot/arm.srdf}\nplanners: [ours-lazyprm@cpu]\nruns: 1\n"
      "time_limit: 20\n");
}

TEST(ProblemSet, RunsEveryProblemUnderItsScenarioAndCountsTheInvalidOnes) {
  const ScratchFolder folder;
  const std::string config = write_problem_set(folder);
  const std::string out = folder.path() + "/out";
  const CommandResult run =
      run_gplan_bench(shell_quoted(config) + " -o " + shell_quoted(out) + " --no-plots");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("loaded 4 problems of"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("3 valid, 1 with the start or goal in collision"), std::string::npos)
      << run.output;
  const std::string summary = read_file(out + "/summary.txt");
  EXPECT_NE(summary.find("solved / valid / total"), std::string::npos) << summary;
  EXPECT_NE(summary.find("2 / 2 / 2"), std::string::npos) << summary;  // beside
  EXPECT_NE(summary.find("1 / 1 / 2"), std::string::npos) << summary;  // front: one invalid
  EXPECT_NE(summary.find("front.0002: "), std::string::npos) << summary;
  // Records: per scenario, runs numbered by problem; the invalid one said so.
  const std::vector<BenchRecord> records = read_bench_csv(out + "/results.csv");
  ASSERT_EQ(records.size(), 4u);
  int invalid = 0;
  for (const BenchRecord& r : records) {
    EXPECT_TRUE(r.scene == "beside" || r.scene == "front") << r.scene;
    if (r.status == "invalid") {
      ++invalid;
      EXPECT_EQ(r.scene, "front");
      EXPECT_EQ(r.run, 1);
      EXPECT_FALSE(r.solved);
    } else {
      EXPECT_TRUE(r.solved) << r.scene << " " << r.run << " " << r.note;
    }
  }
  EXPECT_EQ(invalid, 1);
  // The problems' scene files are kept with the results.
  EXPECT_TRUE(fs::is_regular_file(out + "/problems/front.0002.yaml"));
  EXPECT_TRUE(fs::is_regular_file(out + "/ompl/beside.log"));
}

// --shard I/N: shard I runs every N-th problem from the I-th, with its run number (the
// problem's index in its scenario); the shards' records joined are the whole set's, and
// --report over them gives the whole set's summary.
TEST(ProblemSet, ShardsRunEveryNthProblemAndJoinIntoTheWholeSet) {
  const ScratchFolder folder;
  const std::string config = write_problem_set(folder);
  // Problems in order: beside.0001, beside.0002, front.0001, front.0002 (invalid).
  std::string joined;
  for (const int shard : {1, 2}) {
    const std::string out = folder.path() + "/shard" + std::to_string(shard);
    const CommandResult run =
        run_gplan_bench(shell_quoted(config) + " -o " + shell_quoted(out) + " --shard " +
                        std::to_string(shard) + "/2 --no-plots");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    const std::vector<BenchRecord> records = read_bench_csv(out + "/results.csv");
    ASSERT_EQ(records.size(), 2u) << run.output;
    for (const BenchRecord& r : records) {
      EXPECT_EQ(r.run, shard - 1) << r.scene;  // the problem's index, not the shard's
      EXPECT_EQ(r.status == "invalid", shard == 2 && r.scene == "front") << r.scene;
    }
    std::string csv = read_file(out + "/results.csv");
    if (shard > 1) csv.erase(0, csv.find('\n') + 1);  // one header
    joined += csv;
  }
  folder.write("joined/results.csv", joined);
  const CommandResult report =
      run_gplan_bench(shell_quoted(config) + " --report " +
                      shell_quoted(folder.path() + "/joined") + " --no-plots");
  ASSERT_EQ(report.exit_code, 0) << report.output;
  EXPECT_NE(report.output.find("2 / 2 / 2"), std::string::npos) << report.output;  // beside
  EXPECT_NE(report.output.find("1 / 1 / 2"), std::string::npos) << report.output;  // front
  for (const char* bad : {"0/2", "3/2", "2", "1/0", "a/2", "1/2x", "-1/2", "1/5"}) {
    const CommandResult run =
        run_gplan_bench(shell_quoted(config) + " -o " + shell_quoted(folder.path() + "/bad") +
                        " --shard " + bad + " --no-plots");
    EXPECT_EQ(run.exit_code, 2) << bad << ": " << run.output;
    EXPECT_NE(run.output.find("--shard"), std::string::npos) << bad << ": " << run.output;
    EXPECT_FALSE(fs::exists(folder.path() + "/bad")) << bad;
  }
}

TEST(ProblemSet, MotionBenchMakersPandaFirstProblemOfEveryScenario) {
  const std::string data = gplanner::testing::shared_data();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)";
  const ScratchFolder folder;
  const std::string panda = data + "/motionbenchmaker/panda";
  const std::string config = folder.write(
      "mbm.yaml", "name: mbm-ci\nkind: planning\nmotionbenchmaker:\n  problems: " + panda +
                      "/problems\n  first: 1\n  robot:\n    urdf: " + panda +
                      "/robot/panda.urdf\n    srdf: " + panda +
                      "/robot/panda.srdf\n    packages: {meshes: " + panda +
                      "/robot/meshes}\nplanners: [ours-lazyprm@cpu]\n"
                      "runs: 1\ntime_limit: 10\n");
  const std::string out = folder.path() + "/out";
  const CommandResult run =
      run_gplan_bench(shell_quoted(config) + " -o " + shell_quoted(out) + " --no-plots");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("7 valid, 0 with the start or goal in collision"), std::string::npos)
      << run.output;
  const std::vector<BenchRecord> records = read_bench_csv(out + "/results.csv");
  EXPECT_EQ(records.size(), 7u);
  for (const BenchRecord& r : records) {
    EXPECT_EQ(r.run, 0) << r.scene;
    EXPECT_NE(r.path_check, "fail") << r.scene << ": " << r.note;
  }
  const std::string summary = read_file(out + "/summary.txt");
  for (const char* scenario :
       {"bookshelf_small_panda", "bookshelf_tall_panda", "bookshelf_thin_panda", "box_panda",
        "cage_panda", "table_pick_panda", "table_under_pick_panda"}) {
    EXPECT_NE(summary.find(scenario), std::string::npos) << scenario << "\n" << summary;
  }
}

}  // namespace
}  // namespace gplan
