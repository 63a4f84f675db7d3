// GPU tests (names contain "Gpu"): the GPU all-points k-NN against the CPU reference on
// seeded random configurations, up to ties. They assert that the GPU ran and skip only
// where there is no device.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gplanner/knn_gpu/nearest_neighbors.h"
#include "knn_gpu/knn_test_support.h"

namespace gplanner {
namespace {

using testing::floating_metric;
using testing::joints_metric;
using testing::planar_metric;
using testing::random_configurations;
using testing::same_tables;
using testing::same_up_to_ties;

#define REQUIRE_GPU()                                                                    \
  do {                                                                                   \
    std::string reason;                                                                  \
    if (!gpu_nearest_neighbors_available(&reason)) GTEST_SKIP() << "no GPU: " << reason; \
  } while (0)

// Runs the GPU search, checks that it really ran, and compares with the CPU reference.
NeighborTable expect_gpu_matches_cpu(GpuNearestNeighbors& gpu, const ConfigurationMetric& metric,
                                     const std::vector<float>& points, int k,
                                     float radius = kUnboundedRadius) {
  const std::size_t n = points.size() / std::max(metric.width(), 1);
  NeighborTable on_gpu = gpu.all_nearest(metric, points.data(), n, k, radius);
  const GpuKnnStats& stats = gpu.last_stats();
  if (n > 1) {
    EXPECT_GT(stats.candidate_pairs, 0u) << "the GPU did no work";
    EXPECT_GT(stats.distance_evaluations, 0u);
    EXPECT_LE(stats.distance_evaluations, stats.candidate_pairs);
    EXPECT_GT(stats.tiles_visited, 0u);
  }
  EXPECT_GT(stats.milliseconds, 0.0);
  EXPECT_EQ(stats.tiles, (n + 31) / 32);
  const NeighborTable on_cpu = all_nearest_neighbors_cpu(metric, points.data(), n, k, radius);
  EXPECT_TRUE(same_up_to_ties(on_cpu, on_gpu, radius));
  std::cout << n << " points, k = " << k << " (" << stats.slices
            << " slices): " << stats.milliseconds << " ms (" << stats.search_milliseconds
            << " ms search), " << stats.candidate_pairs << " candidate pairs ("
            << 100.0 * stats.candidate_pairs / (double(n) * n) << "% of n^2), "
            << stats.distance_evaluations << " exact distances, " << stats.tiles_visited
            << " tiles loaded on " << gpu.device_name() << "\n";
  return on_gpu;
}

TEST(KnnGpu, MatchesCpuReferenceFloatingBase) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  EXPECT_FALSE(gpu.device_name().empty());
  expect_gpu_matches_cpu(gpu, floating_metric(0),
                         random_configurations(floating_metric(0), 4000, 101), 15);
  expect_gpu_matches_cpu(gpu, floating_metric(3),
                         random_configurations(floating_metric(3), 3001, 102), 10);
}

TEST(KnnGpu, MatchesCpuReferencePlanarBaseWithContinuousJoint) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  expect_gpu_matches_cpu(gpu, planar_metric(1), random_configurations(planar_metric(1), 3000, 103),
                         12);
  expect_gpu_matches_cpu(gpu, planar_metric(4), random_configurations(planar_metric(4), 2500, 104),
                         8);
}

TEST(KnnGpu, MatchesCpuReferenceJointsOnly) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  expect_gpu_matches_cpu(gpu, joints_metric(7), random_configurations(joints_metric(7), 2000, 105),
                         20);
}

// Small sets are searched in slices of the candidate tiles, merged after (so that the
// GPU has work for more than one warp per 32 points); large ones in one. Both match the
// CPU reference.
TEST(KnnGpu, MatchesCpuReferenceInSlicesAndInOne) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  const ConfigurationMetric m = planar_metric(7);  // like pr2_base_arm
  expect_gpu_matches_cpu(gpu, m, random_configurations(m, 2002, 110), 15);
  EXPECT_EQ(gpu.last_stats().slices, 16);
  expect_gpu_matches_cpu(gpu, m, random_configurations(m, 40000, 111), 15);
  EXPECT_EQ(gpu.last_stats().slices, 1);
}

TEST(KnnGpu, BreaksExactTiesLikeTheCpuReference) {
  REQUIRE_GPU();
  // Integer joints, none continuous: every distance is exact in float on both sides, with
  // ties everywhere, so the tables must be identical.
  ConfigurationMetric m = joints_metric(5);
  m.continuous_mask = 0;
  std::vector<float> points = random_configurations(m, 2000, 106);
  for (float& x : points) x = std::round(x);
  GpuNearestNeighbors gpu;
  const NeighborTable on_gpu = gpu.all_nearest(m, points.data(), 2000, 15);
  EXPECT_GT(gpu.last_stats().candidate_pairs, 0u);
  EXPECT_TRUE(same_tables(all_nearest_neighbors_cpu(m, points.data(), 2000, 15), on_gpu));
}

TEST(KnnGpu, MatchesCpuReferenceWithRadius) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  for (const ConfigurationMetric& m : {floating_metric(0), planar_metric(2), joints_metric(4)}) {
    const std::vector<float> points = random_configurations(m, 2500, 107);
    const NeighborTable five = all_nearest_neighbors_cpu(m, points.data(), 2500, 5);
    const float radius = five.distance(0, 4);  // some rows full, some short
    const NeighborTable on_gpu = expect_gpu_matches_cpu(gpu, m, points, 16, radius);
    for (std::size_t i = 0; i < on_gpu.rows; ++i) {
      for (int r = 0; r < on_gpu.count(i); ++r)
        ASSERT_LE(on_gpu.distance(i, r), radius * (1 + 1e-6f));
    }
  }
}

TEST(KnnGpu, MatchesCpuReferenceForLargerK) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  const ConfigurationMetric m = floating_metric(2);
  const std::vector<float> points = random_configurations(m, 1500, 108);
  expect_gpu_matches_cpu(gpu, m, points, 17);  // the 32-slot kernel
  expect_gpu_matches_cpu(gpu, m, points, kMaxGpuNeighbors);
  EXPECT_THROW(gpu.all_nearest(m, points.data(), 1500, kMaxGpuNeighbors + 1),
               std::invalid_argument);
  EXPECT_THROW(gpu.all_nearest(m, points.data(), 1500, 0), std::invalid_argument);
}

TEST(KnnGpu, PadsSmallSetsAndReusesBuffers) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  const ConfigurationMetric m = floating_metric(1);
  const NeighborTable none = gpu.all_nearest(m, nullptr, 0, 4);
  EXPECT_EQ(none.rows, 0u);
  EXPECT_TRUE(none.indices.empty());
  for (std::size_t n :
       {std::size_t(1), std::size_t(5), std::size_t(33), std::size_t(3000), std::size_t(70)}) {
    const std::vector<float> points = random_configurations(m, n, 109 + n);
    const NeighborTable table = gpu.all_nearest(m, points.data(), n, 10);
    EXPECT_TRUE(same_up_to_ties(all_nearest_neighbors_cpu(m, points.data(), n, 10), table))
        << n << " points";
    if (n <= 10) {
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(table.count(i), static_cast<int>(n) - 1);
    }
  }
}

// nearest_rows() is all_nearest()'s search with only some rows brought back: those rows
// equal the table's exactly, in one slice and in several, alone or after other calls.
TEST(KnnGpu, RowsAreThoseOfTheWholeTable) {
  REQUIRE_GPU();
  GpuNearestNeighbors gpu;
  const ConfigurationMetric m = floating_metric(1);
  for (const std::size_t n : {std::size_t(1500), std::size_t(40000), std::size_t(70)}) {
    const std::vector<float> points = random_configurations(m, n, 111 + n);
    const int k = 15;
    const NeighborTable table = gpu.all_nearest(m, points.data(), n, k);
    ASSERT_TRUE(same_up_to_ties(all_nearest_neighbors_cpu(m, points.data(), n, k), table));
    for (const auto& [first, end] :
         {std::pair<std::size_t, std::size_t>{0, n}, {n / 2, n}, {n / 3, n / 3 + 7}, {n, n}}) {
      std::vector<int> rows((end - first) * k, -2);
      gpu.nearest_rows(m, points.data(), n, k, first, end, rows.data());
      EXPECT_GT(gpu.last_stats().candidate_pairs, 0u) << "the GPU did no work";
      const std::vector<int> expected(table.indices.begin() + first * k,
                                      table.indices.begin() + end * k);
      EXPECT_EQ(rows, expected) << n << " points, rows " << first << " to " << end;
    }
    int unused = 0;
    EXPECT_THROW(gpu.nearest_rows(m, points.data(), n, k, n / 2, n + 1, &unused),
                 std::invalid_argument);
    EXPECT_THROW(gpu.nearest_rows(m, points.data(), n, k, n / 2 + 1, n / 2, &unused),
                 std::invalid_argument);
    EXPECT_EQ(unused, 0);
  }
  gpu.nearest_rows(m, nullptr, 0, 4, 0, 0, nullptr);  // no points: nothing to do
}

}  // namespace
}  // namespace gplanner
