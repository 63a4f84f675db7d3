// `gplan bench` of kind broad-phase through the real binary: CI's small configuration
// writes its CSV, tables and plots, every method that ran agreeing with the reference;
// options that do not apply and bad keys are refused.

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

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
using gplanner::testing::split_fields;

std::string ci_config() { return project_root() + "/benchmarks/config/broad_phase_ci.yaml"; }

TEST(GplanBenchBroadPhase, CiConfigurationWritesCsvTablesAndPlots) {
  const ScratchFolder folder;
  const std::string out = folder.path() + "/broad phase";
  const CommandResult run = run_gplan_bench(ci_config() + " -o " + shell_quoted(out));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("[1/3] 64 spheres"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("[3/3] 2000 spheres"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("MISMATCH"), std::string::npos) << run.output;

  // 3 counts x 6 methods; the CPU methods ran at every count, the GPU ones where there is
  // a GPU (else a note says why not).
  std::stringstream csv(read_file(out + "/results.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line,
            "count,method,frames,pairs_mean,mean_ms,median_ms,min_ms,max_ms,fps_mean,speedup,"
            "reruns,mismatches,note");
  int rows = 0, gpu_rows_run = 0;
  while (std::getline(csv, line)) {
    SCOPED_TRACE(line);
    const std::vector<std::string> f = split_fields(line);
    ASSERT_GE(f.size(), 12u);
    ++rows;
    const bool gpu = f[1].rfind("gpu-", 0) == 0;
    const int frames = std::stoi(f[2]);
    if (!gpu) {
      EXPECT_GE(frames, 2);
      EXPECT_LE(frames, 20);
    }
    if (frames > 0) {
      gpu_rows_run += gpu;
      EXPECT_GT(std::stod(f[5]), 0.0);                               // median_ms
      EXPECT_GT(std::stod(f[8]), 0.0);                               // fps_mean
      EXPECT_EQ(f[11], "0");                                         // mismatches
      if (f[0] == "2000") EXPECT_GT(std::stod(f[3]), 10.0);          // pairs per frame
      if (f[1] == "cpu-all-pairs") EXPECT_EQ(std::stod(f[9]), 1.0);  // its own speed-up
    } else {
      EXPECT_TRUE(gpu);
      EXPECT_NE(line.find("no GPU can be used here"), std::string::npos);
    }
  }
  EXPECT_EQ(rows, 18);
  if (gpu_rows_run == 0)
    EXPECT_NE(run.output.find("left out: no GPU can be used here"), std::string::npos);

  const std::string md = read_file(out + "/results.md");
  EXPECT_NE(md.find("## The seed's Table I beside ours"), std::string::npos) << md;
  EXPECT_NE(md.find("| 64 | 59.31 | 36.49 | 0.62 | "), std::string::npos) << md;
  EXPECT_NE(md.find("| 2000 | "), std::string::npos) << md;
  EXPECT_NE(md.find("## Fastest method (crossovers)"), std::string::npos) << md;
  EXPECT_NE(run.output.find("## Median frame time (ms) per method"), std::string::npos);
  EXPECT_EQ(read_file(out + "/config.yaml"), read_file(ci_config()));
  EXPECT_FALSE(fs::exists(out + "/results.partial.csv"));
  if (run.output.find("notice: no plots") == std::string::npos) {
    EXPECT_TRUE(fs::is_regular_file(out + "/plots/broad_phase.png")) << run.output;
    EXPECT_TRUE(fs::is_regular_file(out + "/plots/broad_phase.svg")) << run.output;
  }
}

TEST(GplanBenchBroadPhase, RefusesWhatDoesNotApplyAndBadKeys) {
  const ScratchFolder folder;
  CommandResult result =
      run_gplan_bench(ci_config() + " -o " + folder.path() + "/a --baseline x.yaml");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--baseline does not apply to the broad-phase study"),
            std::string::npos)
      << result.output;
  const std::string bad = folder.write(
      "bad.yaml", "kind: broad-phase\nmethods: [cpu-all-pairs]\ncounts: [64]\nframez: 3\n");
  result = run_gplan_bench(bad + " -o " + folder.path() + "/b");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find(bad + ":4: framez: unknown key"), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(folder.path() + "/b"));
}

}  // namespace
}  // namespace gplan
