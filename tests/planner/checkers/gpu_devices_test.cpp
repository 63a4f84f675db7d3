// Choosing the GPU (issue 36): a checker and a k-NN search on each device the process
// sees answer as on the first, a checker on every device splits a large batch across
// them and answers as one device does, and a device that is not there is said. The GPU
// tests (names with "Gpu") skip only where there is no device; the parts that need two
// devices say so where there is one.

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/common/gpu_device.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplanner {
namespace {

Scene pr2_scene() { return load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml"); }

// The kernels under test: every call on the GPU.
GpuCheckerOptions on_device(int device) {
  GpuCheckerOptions options;
  options.host_calls_up_to = 0;
  options.device = device;
  return options;
}

// Without a GPU the gpu backend runs as the cpu one, whatever device was asked for (and
// says why); with GPUs, a device beyond those the process sees is refused, naming them.
TEST(GpuDevices, AnAbsentDeviceIsSaid) {
  const Scene scene = pr2_scene();
  std::string reason;
  const int count = gpu_device_count(&reason);
  CheckerOptions options;
  options.gpu.device = count + 3;
  std::string notice;
  if (count == 0) {
    EXPECT_FALSE(reason.empty());
    const auto checker = make_collision_checker(scene, "gpu", options, &notice);
    EXPECT_EQ(checker->backend(), "cpu");
    EXPECT_EQ(checker->gpu_device(), -1);
    EXPECT_NE(notice.find("no GPU"), std::string::npos) << notice;
    EXPECT_FALSE(query_gpu_device(count + 3).available);
    return;
  }
  try {
    make_collision_checker(scene, "gpu", options, &notice);
    FAIL() << "a checker on device " << options.gpu.device << " of " << count;
  } catch (const std::invalid_argument& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("device " + std::to_string(count + 3)), std::string::npos) << what;
    EXPECT_NE(what.find("sees " + std::to_string(count) + " CUDA device"), std::string::npos)
        << what;
  }
}

TEST(GpuDevicesGpu, EveryDeviceAnswersAsTheFirst) {
  REQUIRE_GPU();
  const Scene scene = pr2_scene();
  const CollisionModel model = build_collision_model(scene);
  const std::size_t n = 20000;
  const std::vector<float> q = testing::sample_configurations(scene, n, 36);
  std::vector<std::uint8_t> first(n);
  GpuBatchChecker(model, on_device(0)).check(q.data(), n, first.data());
  const std::size_t colliding = std::count(first.begin(), first.end(), 1);
  ASSERT_GT(colliding, n / 20);  // a mix: the comparison says something
  ASSERT_LT(colliding, n - n / 20);
  const int count = gpu_device_count();
  for (int d = 0; d < count; ++d) {
    SCOPED_TRACE(d);
    GpuBatchChecker checker(model, on_device(d));
    EXPECT_EQ(checker.devices(), std::vector<int>{d});
    std::vector<std::uint8_t> verdicts(n, 2);
    checker.check(q.data(), n, verdicts.data());
    EXPECT_EQ(verdicts, first);
  }
}

TEST(GpuDevicesGpu, EveryDeviceTogetherSplitsALargeBatch) {
  REQUIRE_GPU();
  const Scene scene = pr2_scene();
  const CollisionModel model = build_collision_model(scene);
  const int count = gpu_device_count();
  GpuBatchChecker all(model, on_device(GpuCheckerOptions::kAllDevices));
  ASSERT_EQ(all.devices().size(), static_cast<std::size_t>(count));
  GpuBatchChecker one(model, on_device(0));
  // Large enough to split, not a multiple of the devices; then a small one (the first
  // device alone).
  for (const std::size_t n : {2 * kSplitBatchesFrom + 7, std::size_t(1000)}) {
    SCOPED_TRACE(n);
    const std::vector<float> q = testing::sample_configurations(scene, n, 37);
    std::vector<std::uint8_t> expected(n), verdicts(n, 2);
    one.check(q.data(), n, expected.data());
    all.check(q.data(), n, verdicts.data());
    EXPECT_EQ(verdicts, expected);
    const GpuCheckStats stats = all.last_stats();
    const bool split = count > 1 && n >= kSplitBatchesFrom;
    EXPECT_GE(stats.chunks, split ? static_cast<std::size_t>(count) : 1u);
    EXPECT_GT(stats.bv_tests, 0u);
  }
  if (count == 1) GTEST_SKIP() << "one GPU: the batch was not split (verdicts checked)";
  EXPECT_NE(all.device_name(), one.device_name());  // "2 x NAME", or the names listed
}

TEST(GpuDevicesGpu, NearestNeighborsOnEveryDevice) {
  REQUIRE_GPU();
  const Scene scene = pr2_scene();
  const ConfigurationMetric metric = make_metric(scene.space, scene.planner);
  const std::size_t n = 3000;
  const std::vector<float> points = testing::sample_configurations(scene, n, 38);
  const NeighborTable first = GpuNearestNeighbors(0).all_nearest(metric, points.data(), n, 8);
  const NeighborTable cpu = all_nearest_neighbors_cpu(metric, points.data(), n, 8);
  ASSERT_EQ(first.indices.size(), n * 8);
  for (int d = 0; d < gpu_device_count(); ++d) {
    SCOPED_TRACE(d);
    const NeighborTable table = GpuNearestNeighbors(d).all_nearest(metric, points.data(), n, 8);
    EXPECT_EQ(table.indices, first.indices);
  }
  // And the distances are the CPU search's (the indices may differ only among ties).
  for (std::size_t i = 0; i < first.distances.size(); ++i)
    ASSERT_NEAR(first.distances[i], cpu.distances[i], 1e-4f * (1 + cpu.distances[i])) << i;
  const int absent = gpu_device_count();
  EXPECT_THROW(GpuNearestNeighbors{absent}, std::runtime_error);
}

// A planner's checker and k-NN on the last device: both there, and the gpu backend's
// checker says so.
TEST(GpuDevicesGpu, ThePlannersPartsFollowTheChosenDevice) {
  REQUIRE_GPU();
  const Scene scene = pr2_scene();
  const int last = gpu_device_count() - 1;
  CheckerOptions options;
  options.gpu.device = last;
  const auto checker = make_collision_checker(scene, "gpu", options);
  ASSERT_EQ(checker->backend(), "gpu");
  EXPECT_EQ(checker->gpu_device(), last);
  EXPECT_EQ(dynamic_cast<GpuChecker&>(*checker).devices(), std::vector<int>{last});
  const auto neighbors = make_neighbor_finder(make_metric(scene.space, scene.planner), "gpu",
                                              nullptr, checker->gpu_device());
  EXPECT_EQ(neighbors->device(), "gpu");
  std::uint8_t verdict = 2;
  checker->check(scene.start.data(), 1, &verdict);
  EXPECT_EQ(verdict, 0);  // the start is free
}

}  // namespace
}  // namespace gplanner
