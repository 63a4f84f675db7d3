// gplan-bench on the GPUs of one host (issue 36): each gpu group's worker gets a GPU of
// its own, named in the progress and in the records' device column; --gpus 1 keeps them
// all on the first. A GPU test: skipped where there is none.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "bench_test_support.h"
#include "gplanner/common/gpu_device.h"
#include "harness/bench_record.h"

namespace gplan {
namespace {

using gplanner::testing::CommandResult;
using gplanner::testing::project_root;
using gplanner::testing::read_file;
using gplanner::testing::run_gplan_bench;
using gplanner::testing::ScratchFolder;
using gplanner::testing::shell_quoted;

TEST(GplanBenchGpu, OurGroupsRunOnEveryGpuAWorkerEach) {
  const int count = gplanner::gpu_device_count();
  if (count == 0) GTEST_SKIP() << "no GPU";
  const ScratchFolder folder;
  const std::string scenes = project_root() + "/scenes/";
  const std::string config = folder.write(
      "gpus.yaml", "name: gpus\nkind: planning\nscenes: [" + scenes + "pr2_base_arm.yaml, " +
                       scenes + "humanoid.yaml, " + scenes + "pr2_reach.yaml, " + scenes +
                       "helicopter.yaml]\nplanners: [ours-auto@gpu]\nruns: 2\n"
                       "time_limit: 10\nseed: 1\n");
  const auto run = [&](const std::string& name, const std::string& options) {
    const std::string out = folder.path() + "/" + name;
    const CommandResult result = run_gplan_bench(shell_quoted(config) + " -o " + shell_quoted(out) +
                                                 " --no-plots " + options);
    EXPECT_EQ(result.exit_code, 0) << result.output;
    const std::vector<BenchRecord> records = read_bench_csv(out + "/results.csv");
    EXPECT_EQ(records.size(), 8u);
    std::set<long long> devices;
    for (const BenchRecord& r : records) {
      EXPECT_TRUE(r.solved) << r.scene << " " << r.note;
      EXPECT_EQ(r.path_check, "pass") << r.scene;
      EXPECT_EQ(r.checker, "gpu");
      EXPECT_GE(r.device, 0);
      EXPECT_LT(r.device, count);
      devices.insert(r.device);
    }
    return std::make_pair(result, devices);
  };
  const auto [every, every_devices] = run("every", "");
  const auto [first, first_devices] = run("first", "--gpus 1");
  EXPECT_EQ(first_devices, std::set<long long>{0});
  if (count == 1) GTEST_SKIP() << "one GPU: every run on it (checked)";
  // Four groups over the GPUs, one worker each at a time: at least two GPUs used, and said.
  EXPECT_GE(every_devices.size(), 2u);
  EXPECT_NE(every.output.find(" on GPU 1\n"), std::string::npos) << every.output;
  EXPECT_NE(every.output.find("GPUs: " + std::to_string(count) + " of the " +
                              std::to_string(count) + " this machine shows"),
            std::string::npos)
      << every.output;
  EXPECT_NE(read_file(folder.path() + "/every/summary.txt").find("runs by GPU: device 0 "),
            std::string::npos);
  EXPECT_EQ(first.output.find(" on GPU "), std::string::npos) << first.output;
}

}  // namespace
}  // namespace gplan
