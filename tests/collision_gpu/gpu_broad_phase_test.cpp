// GPU tests (names contain "Gpu"): every GPU broad phase returns exactly the pair set of
// the CPU all-pairs (or, at large counts, of the CPU sort-and-sweep, which the CPU tests
// hold equal to it) on seeded scenes. They assert that the GPU ran and skip only where
// there is no device.

#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "collision_gpu/sphere_scenes.h"
#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/collision_gpu/gpu_broad_phase.h"

namespace gplanner {
namespace {

using testing::SphereScene;

#define REQUIRE_GPU()                                                              \
  do {                                                                             \
    std::string reason;                                                            \
    if (!gpu_broad_phase_available(&reason)) GTEST_SKIP() << "no GPU: " << reason; \
  } while (0)

const BroadPhaseMethod kGpuMethods[] = {
    BroadPhaseMethod::kGpuAllPairs, BroadPhaseMethod::kGpuSortSweep, BroadPhaseMethod::kGpuGrid};

// The CPU pairs in canonical order: all pairs up to 20,000 spheres, sort-and-sweep above.
std::vector<SpherePair> cpu_reference(const SphereScene& scene) {
  std::vector<SpherePair> pairs;
  if (scene.size() <= 20000) {
    all_pairs_cpu(scene.arrays(), &pairs);
  } else {
    sort_sweep_cpu(scene.arrays(), &pairs);
    sort_pairs(&pairs);
  }
  return pairs;
}

// Every GPU method (gpu-all-pairs up to `all_pairs_up_to` spheres) against the CPU.
void expect_gpu_matches_cpu(GpuBroadPhase& gpu, const SphereScene& scene, const char* what,
                            std::size_t all_pairs_up_to = 100000) {
  SCOPED_TRACE(what);
  const std::vector<SpherePair> expected = cpu_reference(scene);
  for (const BroadPhaseMethod method : kGpuMethods) {
    if (method == BroadPhaseMethod::kGpuAllPairs && scene.size() > all_pairs_up_to) continue;
    SCOPED_TRACE(broad_phase_method_name(method));
    std::vector<SpherePair> pairs;
    gpu.find_pairs(method, scene.arrays(), &pairs);
    const GpuBroadPhaseStats& stats = gpu.last_stats();
    EXPECT_EQ(stats.pairs, pairs.size());
    if (scene.size() >= 2) {
      EXPECT_GT(stats.kernels, 0) << "the GPU did no work";
      EXPECT_GT(stats.milliseconds, 0.0);
    }
    sort_pairs(&pairs);
    EXPECT_EQ(pairs.size(), expected.size());
    EXPECT_TRUE(pairs == expected) << "the pair sets differ";
    std::cout << what << ": " << scene.size() << " spheres, " << broad_phase_method_name(method)
              << ": " << pairs.size() << " pairs in " << stats.milliseconds << " ms ("
              << stats.kernels << " kernels, " << stats.reruns << " re-runs) on "
              << gpu.device_name() << "\n";
  }
}

TEST(BroadPhaseGpu, SmallCountsAndTouchingCases) {
  REQUIRE_GPU();
  GpuBroadPhase gpu;
  EXPECT_FALSE(gpu.device_name().empty());
  SphereScene scene;
  expect_gpu_matches_cpu(gpu, scene, "none");
  scene.add(0, 0, 0, 1);
  expect_gpu_matches_cpu(gpu, scene, "one");
  scene.add(2, 0, 0, 1);
  expect_gpu_matches_cpu(gpu, scene, "two touching");
  for (const float origin : {0.f, -3.f, 1000.f, 65536.f})
    expect_gpu_matches_cpu(gpu, testing::lattice_spheres(12, origin, 0.5f), "touching lattice");
  expect_gpu_matches_cpu(gpu, testing::lattice_spheres(12, 0.f, 0.49f), "apart lattice");
  SphereScene points;
  for (int i = 0; i < 300; ++i) points.add(1.f, 2.f, 3.f, 0.f);  // every pair at one point
  points.add(1e-30f, 0.f, 0.f, 0.f);
  points.add(0.f, 0.f, 0.f, 0.f);
  expect_gpu_matches_cpu(gpu, points, "equal points");
}

TEST(BroadPhaseGpu, SeedCountsUniformClusteredMixed) {
  REQUIRE_GPU();
  GpuBroadPhase gpu;
  for (const std::size_t n : {64, 128, 192, 256, 320, 1000, 5000}) {
    expect_gpu_matches_cpu(gpu, testing::uniform_spheres(n, n, 20.f, 0.2f, 0.8f), "uniform");
    expect_gpu_matches_cpu(gpu, testing::clustered_spheres(n, n + 1, 4), "clustered");
    expect_gpu_matches_cpu(gpu, testing::mixed_radii_spheres(n, n + 2, 40.f), "mixed radii");
  }
}

// Far more pairs than the buffer holds at first: it grows to the exact count and the
// pair kernel runs again, once; the next frame needs no re-run.
TEST(BroadPhaseGpu, PairBufferOverflowRunsAgainWithTheExactCount) {
  REQUIRE_GPU();
  const std::size_t n = 3000;
  const SphereScene scene = testing::uniform_spheres(n, 8, 1.f, 2.f, 3.f);  // all overlap
  for (const BroadPhaseMethod method : kGpuMethods) {
    SCOPED_TRACE(broad_phase_method_name(method));
    GpuBroadPhase gpu;
    std::vector<SpherePair> pairs;
    gpu.find_pairs(method, scene.arrays(), &pairs);
    EXPECT_EQ(pairs.size(), n * (n - 1) / 2);
    EXPECT_EQ(gpu.last_stats().reruns, 1);
    EXPECT_GE(gpu.last_stats().pair_capacity, n * (n - 1) / 2);
    gpu.find_pairs(method, scene.arrays(), &pairs);
    EXPECT_EQ(gpu.last_stats().reruns, 0);
    sort_pairs(&pairs);
    EXPECT_TRUE(pairs == cpu_reference(scene));
  }
}

TEST(BroadPhaseGpu, LargeScenesUpTo200k) {
  REQUIRE_GPU();
  GpuBroadPhase gpu;
  // About one overlapping neighbour for every two spheres at every count (uniform).
  for (const std::size_t n : {20000, 200000}) {
    const float side = 1.6f * std::cbrt(float(n));
    expect_gpu_matches_cpu(gpu, testing::uniform_spheres(n, n + 3, side, 0.3f, 0.5f), "uniform");
    expect_gpu_matches_cpu(gpu, testing::clustered_spheres(n, n + 4, 50), "clustered", 20000);
    expect_gpu_matches_cpu(gpu, testing::mixed_radii_spheres(n, n + 5, 4 * side), "mixed radii",
                           20000);
  }
}

TEST(BroadPhaseGpu, RefusesBadSpheresAndCpuMethods) {
  REQUIRE_GPU();
  GpuBroadPhase gpu;
  std::vector<SpherePair> pairs;
  SphereScene scene = testing::uniform_spheres(1000, 9, 5.f, 0.1f, 0.2f);
  scene.centers[3 * 700 + 2] = std::numeric_limits<float>::quiet_NaN();
  for (const BroadPhaseMethod method : kGpuMethods) {
    try {
      gpu.find_pairs(method, scene.arrays(), &pairs);
      FAIL() << broad_phase_method_name(method) << " took a NaN centre";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("sphere 700"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(gpu.find_pairs(BroadPhaseMethod::kCpuAllPairs, scene.arrays(), &pairs),
               std::invalid_argument);
  // And a good frame after the bad ones.
  expect_gpu_matches_cpu(gpu, testing::uniform_spheres(1000, 10, 5.f, 0.1f, 0.2f), "after");
}

}  // namespace
}  // namespace gplanner
