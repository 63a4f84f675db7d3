// gplan-bench through the real binary: CI's small configuration (cpu and fcl) against
// its stored baseline, a planted regression, a path that fails the FCL re-check, and
// outputs that must not be written.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "harness/bench_baseline.h"
#include "harness/bench_record.h"
#include "bench_test_support.h"

namespace gplan {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::CommandResult;
using gplanner::testing::project_root;
using gplanner::testing::read_file;
using gplanner::testing::run_gplan;
using gplanner::testing::run_gplan_bench;
using gplanner::testing::ScratchFolder;
using gplanner::testing::shell_quoted;

std::string config(const std::string& name) { return project_root() + "/benchmarks/config/" + name; }

// A baseline faster and more successful than `run`: every group's median time a tenth,
// its success rate 1.
std::string planted_baseline(const ScratchFolder& folder, const std::string& run_dir) {
  const std::string saved = folder.path() + "/saved.yaml";
  const CommandResult report =
      run_gplan_bench(config("ci_small.yaml") + " --report " + shell_quoted(run_dir) +
                " --no-plots --save-baseline " + shell_quoted(saved));
  EXPECT_EQ(report.exit_code, 0) << report.output;
  std::vector<GroupSummary> groups = load_baseline(saved);
  // Shorter paths than the run's (lengths follow the seeds, whatever the machine's speed;
  // a faster time alone may stay within the configuration's time floor on a fast machine).
  for (GroupSummary& g : groups) {
    g.median_time_s /= 10;
    g.median_length /= 2;
    g.success_rate = 1;
  }
  const std::string planted = folder.path() + "/planted.yaml";
  save_baseline(planted, "planted", groups);
  return planted;
}

TEST(GplanBench, CiConfigurationPassesAgainstItsStoredBaselineAndAPlantedRegressionFails) {
  const ScratchFolder folder;
  const std::string out = folder.path() + "/run one";
  const CommandResult run =
      run_gplan_bench(config("ci_small.yaml") + " -o " + shell_quoted(out) +
                " --baseline " + config("ci_small.baseline.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("within tolerance"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("[1/2] pr2_base_arm ours-lazyprm@cpu: 3 runs"), std::string::npos)
      << run.output;

  // Every run recorded, each with its own seed; every path re-checked and free.
  const std::vector<BenchRecord> records = read_bench_csv(out + "/results.csv");
  ASSERT_EQ(records.size(), 6u);
  for (std::size_t i = 0; i < records.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(records[i].experiment, "ci-small");
    EXPECT_EQ(records[i].scene, "pr2_base_arm");
    EXPECT_EQ(records[i].seed, 1u + i % 3);
    EXPECT_TRUE(records[i].solved) << records[i].note;
    EXPECT_EQ(records[i].path_check, "pass");
    EXPECT_GT(records[i].time_s, 0);
    EXPECT_GT(records[i].simplified_length, 0);
    EXPECT_GT(records[i].memory_mb, 0);
    EXPECT_EQ(records[i].device, -1);  // cpu and fcl: no GPU
  }
  EXPECT_EQ(records[0].planner, "ours-lazyprm");
  EXPECT_EQ(records[0].checker, "cpu");
  EXPECT_EQ(records[3].planner, "ompl-rrtconnect");
  EXPECT_EQ(records[3].checker, "fcl");
  // OMPL's runs: the time in collision checks measured, part of the plan time (RRTConnect
  // with FCL spends most of it there); ours: not measured.
  for (std::size_t i = 3; i < records.size(); ++i) {
    EXPECT_GT(records[i].check_time_s, 0.1 * records[i].time_s) << i;
    EXPECT_LE(records[i].check_time_s, records[i].time_s) << i;
  }
  EXPECT_TRUE(std::isnan(records[0].check_time_s));
  // Ours: where the time went, stage by stage, within the plan time; OMPL's: not measured.
  for (std::size_t i = 0; i < 3; ++i) {
    const BenchRecord& r = records[i];
    const double stages = r.sampling_s + r.state_checks_s + r.knn_s + r.search_s + r.edge_checks_s +
                          r.simplify_time_s;
    EXPECT_GT(r.state_checks_s, 0) << i;
    EXPECT_GT(r.search_s, 0) << i;
    EXPECT_GT(stages, 0.5 * r.time_s) << i;
    EXPECT_LE(stages, r.time_s * (1 + 1e-9)) << i;
    EXPECT_GE(r.rounds, 1) << i;
  }
  for (std::size_t i = 3; i < records.size(); ++i) EXPECT_TRUE(std::isnan(records[i].knn_s)) << i;
  EXPECT_NE(read_file(out + "/summary.txt").find("stages (our planners"), std::string::npos);
  // OMPL's runs differ from each other (OMPL's generator seeded per run).
  EXPECT_NE(records[3].length, records[4].length);

  // The other outputs.
  EXPECT_NE(read_file(out + "/summary.txt").find("ompl-rrtconnect@fcl"), std::string::npos);
  EXPECT_EQ(read_file(out + "/ompl/pr2_base_arm.log").rfind("OMPL version", 0), 0u);
  EXPECT_EQ(read_file(out + "/config.yaml"), read_file(config("ci_small.yaml")));
  for (const char* figure : {"plan_times", "pr2_base_arm"}) {
    EXPECT_TRUE(fs::is_regular_file(out + "/plots/" + figure + ".png")) << figure;
    EXPECT_TRUE(fs::is_regular_file(out + "/plots/" + figure + ".svg")) << figure;
  }

  // A planted regression: the same runs against a faster, more successful baseline.
  const std::string planted = planted_baseline(folder, out);
  const CommandResult report = run_gplan_bench(config("ci_small.yaml") + " --report " +
                                         shell_quoted(out) + " --no-plots --baseline " + planted);
  EXPECT_EQ(report.exit_code, 5) << report.output;
  EXPECT_NE(report.output.find("REGRESSION"), std::string::npos) << report.output;
  EXPECT_NE(report.output.find("regression: pr2_base_arm ours-lazyprm@cpu: median path length"),
            std::string::npos)
      << report.output;
  // And a new run against it.
  const CommandResult again =
      run_gplan_bench(config("ci_small.yaml") + " -o " + shell_quoted(folder.path() + "/two") +
                " --no-plots --baseline " + planted);
  EXPECT_EQ(again.exit_code, 5) << again.output;
}

TEST(GplanBench, APathThatFailsTheFclRecheckExits3WhateverTheBaseline) {
  const ScratchFolder folder;
  BenchRecord record;
  record.experiment = "ci-small";
  record.scene = "pr2_base_arm";
  record.planner = "ompl-rrtconnect";
  record.checker = "fcl";
  record.status = "exact";
  record.solved = true;
  record.time_s = 0.5;
  record.simplified_length = 3;
  record.seed = 9;
  record.path_check = "fail";
  record.note = "FCL re-check: segment 2 (waypoints 2 to 3) collides at 1/10 of the edge resolution";
  std::ofstream csv(folder.path() + "/results.csv");
  write_bench_csv_header(csv);
  write_bench_csv_line(csv, record);
  csv.close();
  const CommandResult report =
      run_gplan_bench(config("ci_small.yaml") + " --report " + folder.path() + " --no-plots");
  EXPECT_EQ(report.exit_code, 3) << report.output;
  EXPECT_NE(report.output.find("FAILED: 1 returned path collide"), std::string::npos) << report.output;
  EXPECT_NE(report.output.find("run 0 (seed 9): FCL re-check: segment 2"), std::string::npos)
      << report.output;
}

TEST(GplanBench, RefusesOutputsThatWouldReplaceSomething) {
  const ScratchFolder folder;
  fs::create_directories(folder.path() + "/used");
  const std::string used = folder.write("used/notes.txt", "mine\n");
  CommandResult result = run_gplan_bench(config("ci_small.yaml") + " -o " +
                                   folder.path() + "/used");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("the folder has files in it"), std::string::npos) << result.output;
  EXPECT_EQ(read_file(used), "mine\n");

  // The baseline to save is a scene of the configuration.
  const std::string scene = folder.write("scene_copy.yaml", read_file(project_root() + "/scenes/piano.yaml"));
  const std::string bench = folder.write(
      "bench.yaml", "kind: planning\nscenes: [scene_copy.yaml]\nplanners: [ours-lazyprm@cpu]\n");
  result = run_gplan_bench(bench + " -o " + folder.path() + "/new --save-baseline " + scene);
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--save-baseline"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(folder.path() + "/new"));
  EXPECT_EQ(read_file(scene), read_file(project_root() + "/scenes/piano.yaml"));

  // No configuration, or two.
  EXPECT_EQ(run_gplan_bench("").exit_code, 2);
  EXPECT_EQ(run_gplan_bench(bench + " " + bench).exit_code, 2);
}

// `gplan bench` is a deprecated alias: gplan-bench runs in gplan's place, its usage,
// messages and exit codes its own.
TEST(GplanBench, GplanBenchRunsTheBenchmarkProgram) {
  const CommandResult none = run_gplan("bench");
  EXPECT_EQ(none.exit_code, 2) << none.output;
  EXPECT_NE(none.output.find("gplan-bench: gplan-bench takes one configuration file"),
            std::string::npos)
      << none.output;
  const CommandResult help = run_gplan("bench --help");
  EXPECT_EQ(help.exit_code, 0) << help.output;
  EXPECT_EQ(help.output.rfind("usage: gplan-bench CONFIG", 0), 0u) << help.output;
}

// gplan started by the dynamic loader (as a relocatable bundle starts it): gplan-bench is
// started the same way. A gplan without gplan-bench beside it says so (exit 1).
TEST(GplanBench, TheAliasFollowsTheLoaderAndSaysWhenGplanBenchIsMissing) {
  const std::string loader = "/lib64/ld-linux-x86-64.so.2";
  if (fs::exists(loader)) {
    const CommandResult help = gplanner::testing::run_program(
        nullptr, loader, shell_quoted(GPLAN_EXECUTABLE) + " bench --help");
    EXPECT_EQ(help.exit_code, 0) << help.output;
    EXPECT_EQ(help.output.rfind("usage: gplan-bench CONFIG", 0), 0u) << help.output;
  }
  const ScratchFolder folder;
  const std::string alone = folder.path() + "/gplan";
  fs::copy_file(GPLAN_EXECUTABLE, alone);
  fs::permissions(alone, fs::perms::owner_all);
  const CommandResult missing =
      gplanner::testing::run_program(nullptr, alone, "bench x.yaml");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("gplan: error: gplan bench runs gplan-bench, which did not start "
                                "from " + folder.path() + "/gplan-bench"),
            std::string::npos)
      << missing.output;
}

// Processes whose command line has `word` in it (zombies excepted).
int processes_running(const std::string& word) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string command_line = read_file(entry.path().string() + "/cmdline");
    std::replace(command_line.begin(), command_line.end(), '\0', ' ');
    const std::string status = read_file(entry.path().string() + "/stat");
    const std::size_t state = status.rfind(')');
    const bool zombie = state != std::string::npos && status.size() > state + 2 && status[state + 2] == 'Z';
    if (!zombie && command_line.find(word) != std::string::npos) ++count;
  }
  return count;
}

TEST(GplanBench, SigtermStopsEveryWorkerAndKeepsTheRunsDone) {
  if (std::getenv("GPLANNER_GPLAN") != nullptr) GTEST_SKIP() << "gplan runs through a wrapper";
  const ScratchFolder folder;
  // OMPL's RRTConnect with FCL on the piano: no path for many seconds.
  const std::string bench = folder.write(
      "bench.yaml", "kind: planning\nscenes: [" + project_root() +
                        "/scenes/piano.yaml]\nplanners: [ompl-rrtconnect@fcl, ompl-prm@fcl]\n"
                        "time_limit: 120\n");
  const std::string out = folder.path() + "/out", log = folder.path() + "/log";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(GPLAN_EXECUTABLE, "gplan", "bench", bench.c_str(), "-o", out.c_str(), "--jobs", "2",
          "--no-plots", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Until both workers run (their groups announced), then the signal.
  const auto started = std::chrono::steady_clock::now();
  while (read_file(log).find("[2/2]") == std::string::npos &&
         std::chrono::steady_clock::now() - started < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const auto sent = std::chrono::steady_clock::now();
  int status = 0;
  pid_t ended = 0;
  while ((ended = waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() - sent < std::chrono::seconds(20)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (ended == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    FAIL() << "still running 20 s after SIGTERM:\n" << read_file(log);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string output = read_file(log);
  EXPECT_LT(seconds, 2.0) << output;
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 143) << output;
  EXPECT_NE(output.find("interrupted by SIGTERM; wrote " + out + "/results.partial.csv (the runs done)"),
            std::string::npos)
      << output;
  // No run finished: the partial CSV holds its header alone; nothing else was written.
  EXPECT_TRUE(read_bench_csv(out + "/results.partial.csv").empty());
  EXPECT_FALSE(fs::exists(out + "/results.csv"));
  EXPECT_FALSE(fs::exists(out + "/summary.txt"));
  // No worker is left behind (workers are forked: their command line is gplan's).
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(processes_running(bench), 0) << "a worker outlived gplan";
}

}  // namespace
}  // namespace gplan
