// gplan bench configurations: the shipped ones load; every kind of mistake is refused
// naming the file, the line and the key, and saying what to change.

#include "harness/bench_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "test_support.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::project_root;
using gplanner::testing::read_file;
using gplanner::testing::ScratchFolder;

TEST(BenchConfig, EveryShippedConfigurationLoads) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(project_root()) / "benchmarks" / "config")) {
    if (entry.path().extension() != ".yaml" ||
        entry.path().string().find(".baseline.") != std::string::npos)
      continue;
    SCOPED_TRACE(entry.path().string());
    // A problem set read from ../shared/data loads where that data is.
    if (gplanner::testing::shared_data().empty() &&
        read_file(entry.path().string()).find("motionbenchmaker:") != std::string::npos)
      continue;
    const BenchConfig config = load_bench_config(entry.path().string());
    if (config.kind != "broad-phase" && !config.problem_set) EXPECT_FALSE(config.scenes.empty());
    if (config.problem_set)  // 7 scenarios x 100 problems, or the first of each
      EXPECT_TRUE(config.problem_set->problems.size() == 700u || config.problem_set->problems.size() == 7u);
    for (const std::string& scene : config.scenes) EXPECT_TRUE(fs::is_regular_file(scene)) << scene;
    ++loaded;
  }
  EXPECT_GE(loaded, 5);
}

TEST(BenchConfig, ReadsEveryKey) {
  const ScratchFolder folder;
  folder.write("a.yaml", "name: x\n");
  const std::string file = folder.write("bench.yaml",
                                        "name: mine\nkind: planning\nscenes: [a.yaml]\n"
                                        "planners: [ours-prm@cpu, ompl-rrtconnect@fcl]\n"
                                        "runs: 4\ntime_limit: 2.5\ngroup_budget: 9\n"
                                        "recheck_refinement: 20\nsimplify: false\nseed: 7\n"
                                        "tolerances: {time_ratio: 2, time_floor: 0.1, "
                                        "success_rate: 0.5, path_length_ratio: 1.1}\n");
  const BenchConfig c = load_bench_config(file);
  EXPECT_EQ(c.name, "mine");
  EXPECT_EQ(c.kind, "planning");
  ASSERT_EQ(c.scenes.size(), 1u);
  EXPECT_EQ(fs::path(c.scenes[0]).filename(), "a.yaml");
  ASSERT_EQ(c.planners.size(), 2u);
  EXPECT_EQ(c.planners[0].label(), "ours-prm@cpu");
  EXPECT_TRUE(c.planners[0].ours());
  EXPECT_FALSE(c.planners[0].single_threaded());
  EXPECT_TRUE(c.planners[1].single_threaded());
  EXPECT_EQ(c.runs, 4);
  EXPECT_DOUBLE_EQ(c.time_limit_s, 2.5);
  EXPECT_DOUBLE_EQ(c.group_budget_s, 9);
  EXPECT_DOUBLE_EQ(c.recheck_refinement, 20);
  EXPECT_FALSE(c.simplify);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_DOUBLE_EQ(c.tolerances.time_ratio, 2);
  EXPECT_DOUBLE_EQ(c.tolerances.time_floor_s, 0.1);
  EXPECT_DOUBLE_EQ(c.tolerances.success_rate, 0.5);
  EXPECT_DOUBLE_EQ(c.tolerances.path_length_ratio, 1.1);
}

struct BadConfig {
  const char* text;
  const char* where;    // "LINE: KEY" expected in the message
  const char* problem;  // a part of the problem
};

class BenchConfigRefuses : public ::testing::TestWithParam<BadConfig> {};

TEST_P(BenchConfigRefuses, NamingLineKeyAndWhatToChange) {
  const ScratchFolder folder;
  folder.write("a.yaml", "name: x\n");
  folder.write("sub/a.yaml", "name: y\n");
  const std::string file = folder.write("bench.yaml", GetParam().text);
  try {
    load_bench_config(file);
    FAIL() << "accepted:\n" << GetParam().text;
  } catch (const gplanner::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file + ":" + GetParam().where), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().problem), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    , BenchConfigRefuses,
    ::testing::Values(
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\nrunz: 3\n",
                  "4: runz", "unknown key"},
        BadConfig{"scenes: [a.yaml]\nplanners: [ours-prm@gpu]\n", "1: kind", "missing"},
        BadConfig{"kind: plan\nscenes: [a.yaml]\n", "1: kind", "not one of planning, queries"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm]\n", "3: planners[0]",
                  "PLANNER@CHECKER"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [rrt@fcl]\n", "3: planners[0]",
                  "PLANNER one of"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu, ours-prm@gpu]\n",
                  "3: planners[1]", "listed twice"},
        BadConfig{"kind: planning\nscenes: [missing.yaml]\nplanners: [ours-prm@gpu]\n",
                  "2: scenes[0]", "missing.yaml"},
        BadConfig{"kind: planning\nscenes: [a.yaml, sub/a.yaml]\nplanners: [ours-prm@gpu]\n",
                  "2: scenes[1]", "rename one file"},
        BadConfig{"kind: planning\nscenes: []\nplanners: [ours-prm@gpu]\n", "2: scenes",
                  "expected a list"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\nruns: 0\n",
                  "4: runs", "whole number from 1"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\nruns: 2.5\n",
                  "4: runs", "whole number"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\ntime_limit: -1\n",
                  "4: time_limit", "above 0"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\ntime_limit: .nan\n",
                  "4: time_limit", "finite"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\nrepeat: 3\n",
                  "4: repeat", "does not apply to kind: planning"},
        BadConfig{"kind: queries\nscenes: [a.yaml]\ntables: [collision-queries]\n"
                  "checkers: [gpu-fast]\n",
                  "4: checkers[0]", "not one of"},
        BadConfig{"kind: queries\nscenes: [a.yaml]\ntables: [everything]\ncheckers: [cpu]\n",
                  "3: tables[0]", "not one of"},
        BadConfig{"kind: queries\nscenes: [a.yaml]\ntables: [local-planning]\ncheckers: [cpu]\n"
                  "runs: 3\n",
                  "5: runs", "does not apply to kind: queries"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\n"
                  "tolerances: {time_ratio: 0.5}\n",
                  "4: tolerances.time_ratio", "at least 1"},
        BadConfig{"kind: planning\nscenes: [a.yaml]\nplanners: [ours-prm@gpu]\n"
                  "tolerances: {success_rate: 2}\n",
                  "4: tolerances.success_rate", "from 0 to 1"},
        BadConfig{"kind: planning\nkind: queries\nscenes: [a.yaml]\n", "2: kind", "twice"},
        // kind: broad-phase
        BadConfig{"kind: broad-phase\nmethods: [cpu-all-pairs]\n", "1: counts", "missing"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-octree]\ncounts: [64]\n", "2: methods[0]",
                  "not one of cpu-all-pairs"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid, gpu-grid]\ncounts: [64]\n",
                  "2: methods[1]", "listed twice"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64, 1]\n", "3: counts[1]",
                  "whole number from 2"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\nscenes: [a.yaml]\n",
                  "4: scenes", "does not apply to kind: broad-phase"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\nruns: 3\n", "4: runs",
                  "does not apply to kind: broad-phase"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\n"
                  "max_count: {cpu-all-pairs: 100}\n",
                  "4: max_count.cpu-all-pairs", "not in methods"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\nradius: [0.5, 0.1]\n",
                  "4: radius", "min <= max"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\nvolume_fraction: 0.9\n",
                  "4: volume_fraction", "at most 0.5"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\nframes: 2\n"
                  "min_frames: 5\n",
                  "5: min_frames", "more than frames"},
        BadConfig{"kind: broad-phase\nmethods: [gpu-grid]\ncounts: [64]\n"
                  "tolerances: {time_ratio: 2}\n",
                  "4: tolerances", "does not apply to kind: broad-phase"}));

TEST(BenchConfig, ReadsTheBroadPhaseKeys) {
  const ScratchFolder folder;
  const std::string file = folder.write(
      "bench.yaml",
      "kind: broad-phase\nmethods: [gpu-grid, cpu-all-pairs]\ncounts: [320, 64]\n"
      "max_count: {cpu-all-pairs: 1000}\nframes: 50\nmin_frames: 4\ncount_budget: 2.5\n"
      "radius: [0.25, 1]\nvolume_fraction: 0.2\nspeed: 0.1\nseed: 3\n");
  const BenchConfig c = load_bench_config(file);
  EXPECT_EQ(c.kind, "broad-phase");
  EXPECT_EQ(c.name, "bench");
  EXPECT_TRUE(c.scenes.empty());
  const BroadPhaseOptions& o = c.broad_phase;
  EXPECT_EQ(o.methods, (std::vector<std::string>{"gpu-grid", "cpu-all-pairs"}));
  EXPECT_EQ(o.counts, (std::vector<std::uint64_t>{64, 320}));  // ascending
  EXPECT_EQ(o.max_count.at("cpu-all-pairs"), 1000u);
  EXPECT_EQ(o.frames, 50);
  EXPECT_EQ(o.min_frames, 4);
  EXPECT_DOUBLE_EQ(o.count_budget_s, 2.5);
  EXPECT_DOUBLE_EQ(o.radius_min, 0.25);
  EXPECT_DOUBLE_EQ(o.radius_max, 1);
  EXPECT_DOUBLE_EQ(o.volume_fraction, 0.2);
  EXPECT_DOUBLE_EQ(o.speed, 0.1);
  EXPECT_EQ(c.seed, 3u);
}

}  // namespace
}  // namespace gplan
