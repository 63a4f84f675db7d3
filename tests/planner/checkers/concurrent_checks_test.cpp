// One checker called from several threads at once: every verdict equals the verdict of
// one thread, on each backend, and the statistics a caller reads are those of one whole
// call. GPU cases (names contain "Gpu") skip without a device and assert that it ran.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr int kThreads = 6;

Scene pr2_base_arm() { return load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml"); }

std::string param_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  name[0] = static_cast<char>(std::toupper(name[0]));
  return name;  // "Fcl", "Cpu", "Gpu": GPU cases match *Gpu*
}

class ConcurrentCheck : public ::testing::TestWithParam<std::string> {};

// Each thread checks every row, starting at its own offset, in calls of 1 to 64 rows:
// single states (as OMPL's isValid) among batches (as motions), all at once.
TEST_P(ConcurrentCheck, EveryVerdictAsOnOneThread) {
  // "GpuRouted": the gpu backend as made by default, small calls answered on the host;
  // "gpu": every call on the GPU.
  const bool routed = GetParam() == "GpuRouted";
  const std::string backend = routed ? "gpu" : GetParam();
  CheckerOptions options;
  if (!routed) options.gpu.host_calls_up_to = 0;
  if (backend == "gpu") {
    const GpuDevice device = query_gpu_device();
    if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  }
  const Scene scene = pr2_base_arm();
  std::string notice;
  const std::unique_ptr<CollisionChecker> checker =
      make_collision_checker(scene, backend, options, &notice);
  ASSERT_EQ(checker->backend(), backend) << notice;
  const std::size_t n = backend == "fcl" ? 1500 : 3000, width = scene.space.width();
  const std::vector<float> q = testing::sample_configurations(scene, n, 18);
  std::vector<std::uint8_t> one_thread(n);
  checker->check(q.data(), n, one_thread.data());
  const std::size_t colliding = std::count(one_thread.begin(), one_thread.end(), 1);
  ASSERT_GT(colliding, n / 10);
  ASSERT_LT(colliding, n - n / 10);

  std::vector<std::vector<std::uint8_t>> seen(kThreads, std::vector<std::uint8_t>(n, 2));
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const std::size_t sizes[] = {1, 1, 5, 1, 64, 1, 17};
      std::size_t done = 0, call = t;
      while (done < n) {
        const std::size_t row = (done + t * n / kThreads) % n;
        const std::size_t count = std::min({sizes[call++ % 7], n - done, n - row});
        checker->check(&q[row * width], count, &seen[t][row]);
        done += count;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    std::size_t wrong = 0, missed = 0;
    for (std::size_t i = 0; i < n; ++i) {
      wrong += seen[t][i] != one_thread[i];
      missed += seen[t][i] == 0 && one_thread[i] == 1;
    }
    EXPECT_EQ(wrong, 0u) << "thread " << t << ": " << missed << " collisions reported free";
  }
  if (backend == "gpu" && !routed) {
    std::vector<std::uint8_t> again(n);
    checker->check(q.data(), n, again.data());
    EXPECT_EQ(again, one_thread);
    const GpuCheckStats stats = dynamic_cast<GpuChecker&>(*checker).last_stats();
    EXPECT_GT(stats.bv_tests, 0u) << "the GPU did no work";
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ConcurrentCheck,
                         ::testing::Values("fcl", "cpu", "gpu", "GpuRouted"), param_name);

// The test counts read while other threads check are always those of one whole call:
// every call checks the same rows, so every read gives that call's counts.
TEST(CpuConcurrentCheck, TestCountsAreThoseOfOneWholeCall) {
  const Scene scene = pr2_base_arm();
  CpuChecker checker(scene);
  const std::size_t n = 48;
  const std::vector<float> q = testing::sample_configurations(scene, n, 5);
  std::vector<std::uint8_t> verdicts(n);
  checker.check(q.data(), n, verdicts.data());
  const unsigned long long bv_tests = checker.bv_tests(), triangle_tests = checker.triangle_tests();
  ASSERT_GT(bv_tests, 0u);
  std::atomic<int> inconsistent{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&] {
      std::vector<std::uint8_t> v(n);
      for (int k = 0; k < 150; ++k) {
        checker.check(q.data(), n, v.data());
        if (checker.bv_tests() != bv_tests || checker.triangle_tests() != triangle_tests)
          ++inconsistent;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(inconsistent, 0);
}

}  // namespace
}  // namespace gplanner
