// CollisionChecker::check_clearances on every backend (GPU cases named Gpu): known
// distances to a wall, clearances that are no number, and, on every shipped scene with
// the clearances certified motions ask (half of each link's displacement bound over a
// short motion), agreement with FCL in double: no body FCL finds closer than its
// clearance reported clear, the extra ones within the band; and the GPU's traversals
// against the cpu backend.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/motion_bound.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

bool gpu_missing(std::string* reason) {
  const GpuDevice device = query_gpu_device();
  *reason = device.reason;
  return !device.available;
}

class ClearancesOn : public ::testing::TestWithParam<std::string> {};

TEST_P(ClearancesOn, KnownDistancesToAWall) {
  std::string reason;
  if (GetParam() == "gpu" && gpu_missing(&reason)) GTEST_SKIP() << "no GPU: " << reason;
  testing::ScratchFolder folder;
  folder.write("cube.obj", testing::kCubeObj);
  const Scene scene = load_scene(folder.write("wall.yaml", testing::kCubeAndThinWallScene));
  const std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, GetParam());
  ASSERT_EQ(checker->backend(), GetParam());
  ASSERT_EQ(scene.robot.links.size(), 1u);
  // The cube's face 5 cm from the wall.
  std::vector<float> q(scene.space.width());
  const std::vector<double> values = {-0.01 - 0.1 - 0.05, 0, 0, 1, 0, 0, 0};
  scene.space.from_file_values(values.data(), q.data());
  const double delta = tolerance_delta(scene);
  const std::vector<float> clearances = {0.0f, float(0.05 - 2 * delta), float(0.05 + 2 * delta),
                                         1.0f, std::numeric_limits<float>::quiet_NaN()};
  std::vector<float> rows;
  for (std::size_t i = 0; i < clearances.size(); ++i) rows.insert(rows.end(), q.begin(), q.end());
  std::vector<std::uint8_t> verdicts(clearances.size(), 9);
  checker->check_clearances(rows.data(), clearances.size(), clearances.data(), verdicts.data());
  EXPECT_EQ(verdicts[0], 0) << "no clearance: free";
  EXPECT_EQ(verdicts[1], 0) << "5 cm away, held to a little less";
  EXPECT_EQ(verdicts[2], 1) << "5 cm away, held to a little more";
  EXPECT_EQ(verdicts[3], 1);
  EXPECT_EQ(verdicts[4], 1) << "a clearance that is no number: never free";
}

INSTANTIATE_TEST_SUITE_P(Backends, ClearancesOn, ::testing::Values("cpu", "fcl", "gpu"),
                         [](const auto& info) {
                           return info.param == "gpu" ? std::string("Gpu") : info.param;
                         });

// Seeded configurations, each with the clearances of a short motion from it (1 % of the
// way toward another configuration), as certified motions ask them.
struct ClearanceBatch {
  std::vector<float> configurations, clearances;
  std::size_t n = 0;
};

ClearanceBatch clearance_batch(const Scene& scene, std::size_t n, unsigned seed) {
  const std::size_t width = scene.space.width(), links = scene.robot.links.size();
  const std::vector<float> q = testing::sample_configurations(scene, 2 * n, seed);
  const MotionBound bound(scene.robot, scene.space);
  ClearanceBatch batch;
  batch.n = n;
  batch.configurations.assign(q.begin(), q.begin() + n * width);
  std::vector<float> near(width);
  std::vector<double> moved(links);
  for (std::size_t i = 0; i < n; ++i) {
    scene.space.interpolate(&q[i * width], &q[(n + i) * width], 0.01, near.data());
    bound.link_displacements(&q[i * width], near.data(), moved.data());
    for (std::size_t l = 0; l < links; ++l) batch.clearances.push_back(float(0.5 * moved[l]));
  }
  return batch;
}

// Verdicts against FCL's at the clearances (none missed) and at the clearances plus the
// band (every extra one within it). FCL's distances take up to 0.1 s a configuration on
// the PR2: batches here stay small.
void expect_within_band(const Scene& scene, const ClearanceBatch& batch,
                        const std::vector<std::uint8_t>& verdicts, const std::string& what) {
  FclChecker fcl(scene);
  std::vector<std::uint8_t> exact(batch.n), outer(batch.n);
  fcl.check_clearances(batch.configurations.data(), batch.n, batch.clearances.data(), exact.data());
  fcl.check_clearances(batch.configurations.data(), batch.n, batch.clearances.data(),
                       tolerance_delta(scene), outer.data());
  std::size_t missed = 0, outside = 0, colliding = 0, free = 0;
  for (std::size_t i = 0; i < batch.n; ++i) {
    missed += exact[i] && !verdicts[i];
    outside += verdicts[i] && !outer[i];
    colliding += exact[i];
    free += !exact[i];
  }
  EXPECT_EQ(missed, 0u) << what << ": closer than the clearance, reported clear";
  EXPECT_EQ(outside, 0u) << what << ": reported closer, FCL finds it clear beyond the band";
  EXPECT_GT(colliding, batch.n / 50) << what << ": a batch with nothing close tests nothing";
  EXPECT_GT(free, batch.n / 50) << what << ": a batch with nothing clear tests nothing";
}

class ClearancesAgreeWithFcl : public ::testing::TestWithParam<std::string> {};

TEST_P(ClearancesAgreeWithFcl, OnTheCpuBackend) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const ClearanceBatch batch = clearance_batch(scene, 60, 17);
  CpuChecker cpu(scene);
  std::vector<std::uint8_t> verdicts(batch.n);
  cpu.check_clearances(batch.configurations.data(), batch.n, batch.clearances.data(),
                       verdicts.data());
  expect_within_band(scene, batch, verdicts, GetParam() + " cpu");
}

// Every traversal against the cpu backend, the same core, on a large batch: the same
// verdicts but for rounding; and on a batch small enough for FCL, within its band.
TEST_P(ClearancesAgreeWithFcl, OnEveryGpuTraversal) {
  std::string reason;
  if (gpu_missing(&reason)) GTEST_SKIP() << "no GPU: " << reason;
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const ClearanceBatch batch = clearance_batch(scene, 5000, 29);
  const ClearanceBatch small = clearance_batch(scene, 60, 31);
  CpuChecker cpu(scene);
  std::vector<std::uint8_t> on_cpu(batch.n);
  cpu.check_clearances(batch.configurations.data(), batch.n, batch.clearances.data(),
                       on_cpu.data());
  std::size_t close = 0;
  for (std::size_t i = 0; i < batch.n; ++i) close += on_cpu[i];
  EXPECT_GT(close, batch.n / 50);
  EXPECT_LT(close, batch.n - batch.n / 50);
  for (const Traversal t : {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced}) {
    for (const bool small_batch : {false, true}) {
      if (small_batch && t != Traversal::kBalanced) continue;
      CheckerOptions options;
      options.gpu.traversal = t;
      options.gpu.warp_per_pair_up_to = small_batch ? batch.n : 0;
      options.gpu.host_calls_up_to = 0;
      const std::unique_ptr<CollisionChecker> gpu = make_collision_checker(scene, "gpu", options);
      ASSERT_EQ(gpu->backend(), "gpu");
      std::vector<std::uint8_t> on_gpu(batch.n);
      gpu->check_clearances(batch.configurations.data(), batch.n, batch.clearances.data(),
                            on_gpu.data());
      const std::string what = GetParam() + " " + traversal_name(t) + (small_batch ? " small" : "");
      std::size_t differ = 0;
      for (std::size_t i = 0; i < batch.n; ++i) differ += on_gpu[i] != on_cpu[i];
      EXPECT_LE(differ, batch.n / 200) << what;
      std::vector<std::uint8_t> on_gpu_small(small.n);
      gpu->check_clearances(small.configurations.data(), small.n, small.clearances.data(),
                            on_gpu_small.data());
      expect_within_band(scene, small, on_gpu_small, what);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ClearancesAgreeWithFcl,
                         ::testing::ValuesIn(testing::shipped_scene_files()),
                         [](const auto& info) { return testing::scene_test_name(info.param); });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ClearancesAgreeWithFcl);

}  // namespace
}  // namespace gplanner
