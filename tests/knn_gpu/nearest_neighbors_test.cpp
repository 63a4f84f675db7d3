// The CPU reference k-NN against the naive computation (every distance, sorted), for a
// floating base with joints, a planar base with a continuous joint, and joints only.

#include "gplanner/knn_gpu/nearest_neighbors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "knn_gpu/knn_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::floating_metric;
using testing::joints_metric;
using testing::naive_neighbors;
using testing::planar_metric;
using testing::random_configurations;
using testing::same_tables;

void expect_matches_naive(const ConfigurationMetric& metric, std::size_t n, int k, float radius,
                          unsigned seed) {
  const std::vector<float> points = random_configurations(metric, n, seed);
  const NeighborTable cpu = all_nearest_neighbors_cpu(metric, points.data(), n, k, radius);
  EXPECT_TRUE(same_tables(naive_neighbors(metric, points.data(), n, nullptr, 0, k, radius), cpu));
}

// Threads the system fails to start (no address space left for their stacks) are not
// fatal: the search runs on those that did (before: std::terminate, the started
// threads' handles destroyed while joinable).
TEST(KnnCpu, ThreadsThatFailToStartLeaveTheRowsToThoseThatDid) {
  const ConfigurationMetric metric = floating_metric(3);
  const std::size_t n = 400;
  const std::vector<float> points = random_configurations(metric, n, 7);
  const NeighborTable expected = naive_neighbors(metric, points.data(), n, nullptr, 0, 5,
                                                 kUnboundedRadius);
  const int code = gplanner::testing::run_with_address_space_to_spare(
      std::size_t(24) << 20, [&] {
        const NeighborTable cpu =
            all_nearest_neighbors_cpu(metric, points.data(), n, 5, kUnboundedRadius, 1024);
        return static_cast<bool>(same_tables(expected, cpu));
      });
  EXPECT_EQ(code, 0) << "0: the right neighbours; 1: wrong ones; 2: threw; 134: terminated";
}

TEST(KnnCpu, MatchesNaiveFloatingBaseWithJoints) {
  expect_matches_naive(floating_metric(3), 700, 12, kUnboundedRadius, 1);
}

TEST(KnnCpu, MatchesNaiveRigidFloatingBase) {
  expect_matches_naive(floating_metric(0), 600, 15, kUnboundedRadius, 2);
}

TEST(KnnCpu, MatchesNaivePlanarBaseWithContinuousJoint) {
  expect_matches_naive(planar_metric(2), 700, 10, kUnboundedRadius, 3);
}

TEST(KnnCpu, MatchesNaiveJointsOnly) {
  expect_matches_naive(joints_metric(7), 700, 9, kUnboundedRadius, 4);
}

TEST(KnnCpu, WrapsContinuousJointsAndHeadings) {
  // Headings 3.1 and -3.1 are 0.083 apart the short way round; 3.1 and 2.5 are 0.6.
  ConfigurationMetric m = planar_metric(1);
  const std::vector<float> points = {0, 0, 3.1f,  0,  //
                                     0, 0, 2.5f,  0,  //
                                     0, 0, -3.1f, 6.2f};
  const NeighborTable table = all_nearest_neighbors_cpu(m, points.data(), 3, 1);
  EXPECT_EQ(table.index(0, 0), 2);
  EXPECT_NEAR(
      table.distance(0, 0),
      m.rotation_weight * (6.2831853f - 6.2f) + m.joint_weight * std::fabs(6.2f - 6.2831853f),
      1e-4);
}

TEST(KnnCpu, RadiusBoundsTheNeighbours) {
  for (const ConfigurationMetric& metric :
       {floating_metric(2), planar_metric(1), joints_metric(4)}) {
    const std::size_t n = 500;
    const std::vector<float> points = random_configurations(metric, n, 5);
    // A radius about the 5th neighbour's distance: some rows full, some short, some empty.
    const NeighborTable unbounded = all_nearest_neighbors_cpu(metric, points.data(), n, 5);
    const float radius = unbounded.distance(0, 4);
    const NeighborTable table = all_nearest_neighbors_cpu(metric, points.data(), n, 20, radius);
    EXPECT_TRUE(
        same_tables(naive_neighbors(metric, points.data(), n, nullptr, 0, 20, radius), table));
    std::size_t short_rows = 0;
    for (std::size_t i = 0; i < n; ++i) {
      for (int r = 0; r < table.count(i); ++r) EXPECT_LE(table.distance(i, r), radius);
      if (table.count(i) < 20) ++short_rows;
    }
    EXPECT_GT(short_rows, 0u);
    // A zero radius leaves exactly the repeated points.
    const NeighborTable zero = all_nearest_neighbors_cpu(metric, points.data(), n, 3, 0.0f);
    EXPECT_TRUE(same_tables(naive_neighbors(metric, points.data(), n, nullptr, 0, 3, 0.0f), zero));
    EXPECT_GE(zero.count(9), 1) << "point 9 repeats an earlier point";
  }
}

TEST(KnnCpu, TiesGoToTheSmallerIndex) {
  // One joint: 0 has neighbours 1 (at +1) and 2 (at -1) at equal distance, then 3 (at +2)
  // and 4 (a copy of 3).
  const ConfigurationMetric m = joints_metric(1);
  ConfigurationMetric line = m;
  line.continuous_mask = 0;
  const std::vector<float> points = {0, 1, -1, 2, 2};
  const NeighborTable table = all_nearest_neighbors_cpu(line, points.data(), 5, 4);
  EXPECT_EQ(std::vector<int>(table.indices.begin(), table.indices.begin() + 4),
            (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(table.index(4, 0), 3);
  // Integer joints: a grid full of exact ties, still identical to the naive answer.
  const std::size_t n = 600;
  std::vector<float> grid = random_configurations(joints_metric(5), n, 6);
  for (float& x : grid) x = std::round(x);
  const NeighborTable tied = all_nearest_neighbors_cpu(joints_metric(5), grid.data(), n, 15);
  EXPECT_TRUE(same_tables(
      naive_neighbors(joints_metric(5), grid.data(), n, nullptr, 0, 15, kUnboundedRadius), tied));
}

TEST(KnnCpu, PadsRowsWhenKExceedsTheOtherPoints) {
  const ConfigurationMetric m = floating_metric(1);
  const std::vector<float> points = random_configurations(m, 4, 7);
  const NeighborTable table = all_nearest_neighbors_cpu(m, points.data(), 4, 6);
  ASSERT_EQ(table.indices.size(), 24u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(table.count(i), 3);
    for (int r = 3; r < 6; ++r) {
      EXPECT_EQ(table.index(i, r), -1);
      EXPECT_TRUE(std::isinf(table.distance(i, r)));
    }
  }
  EXPECT_TRUE(
      same_tables(naive_neighbors(m, points.data(), 4, nullptr, 0, 6, kUnboundedRadius), table));
}

TEST(KnnCpu, HandlesNoPointAndOnePoint) {
  const ConfigurationMetric m = floating_metric(0);
  const NeighborTable none = all_nearest_neighbors_cpu(m, nullptr, 0, 5);
  EXPECT_EQ(none.rows, 0u);
  EXPECT_EQ(none.k, 5);
  EXPECT_TRUE(none.indices.empty());
  const std::vector<float> point = {1, 2, 3, 1, 0, 0, 0};
  const NeighborTable one = all_nearest_neighbors_cpu(m, point.data(), 1, 3);
  ASSERT_EQ(one.rows, 1u);
  EXPECT_EQ(one.count(0), 0);
  EXPECT_EQ(one.indices, (std::vector<int>{-1, -1, -1}));
}

TEST(KnnCpu, QueriesMatchNaive) {
  for (const ConfigurationMetric& metric :
       {floating_metric(2), planar_metric(2), joints_metric(6)}) {
    const std::size_t n = 400, m = 37;
    const std::vector<float> points = random_configurations(metric, n, 8);
    const std::vector<float> queries = random_configurations(metric, m, 9);
    const NeighborTable table =
        nearest_neighbors_cpu(metric, points.data(), n, queries.data(), m, 11);
    EXPECT_TRUE(same_tables(
        naive_neighbors(metric, points.data(), n, queries.data(), m, 11, kUnboundedRadius), table));
    // A query equal to a point finds it at distance 0.
    const NeighborTable self =
        nearest_neighbors_cpu(metric, points.data(), n, points.data() + 5 * metric.width(), 1, 1);
    EXPECT_EQ(self.index(0, 0), 5);
    EXPECT_EQ(self.distance(0, 0), 0.0f);
    const float radius = table.distance(0, 3);
    EXPECT_TRUE(same_tables(
        naive_neighbors(metric, points.data(), n, queries.data(), m, 11, radius),
        nearest_neighbors_cpu(metric, points.data(), n, queries.data(), m, 11, radius)));
  }
}

TEST(KnnCpu, ThreadCountDoesNotChangeTheResult) {
  const ConfigurationMetric m = floating_metric(2);
  const std::vector<float> points = random_configurations(m, 900, 10);
  const NeighborTable all_threads = all_nearest_neighbors_cpu(m, points.data(), 900, 8);
  for (int threads : {1, 3}) {
    EXPECT_TRUE(same_tables(all_threads, all_nearest_neighbors_cpu(m, points.data(), 900, 8,
                                                                   kUnboundedRadius, threads)));
  }
}

TEST(KnnCpu, RejectsBadArguments) {
  const ConfigurationMetric m = floating_metric(0);
  const std::vector<float> points = random_configurations(m, 10, 11);
  EXPECT_THROW(all_nearest_neighbors_cpu(m, points.data(), 10, 0), std::invalid_argument);
  EXPECT_THROW(all_nearest_neighbors_cpu(m, points.data(), 10, 3, -1.0f), std::invalid_argument);
  EXPECT_THROW(all_nearest_neighbors_cpu(m, points.data(), 10, 3, std::nanf("")),
               std::invalid_argument);
  ConfigurationMetric negative = m;
  negative.position_weight = -1;
  EXPECT_THROW(all_nearest_neighbors_cpu(negative, points.data(), 10, 3), std::invalid_argument);
  EXPECT_THROW(nearest_neighbors_cpu(m, points.data(), 10, points.data(), 1, 0),
               std::invalid_argument);
}

TEST(KnnDevice, GpuSearchSaysWhyItCannotRun) {
  std::string reason;
  if (gpu_nearest_neighbors_available(&reason)) GTEST_SKIP() << "a GPU is present";
  EXPECT_FALSE(reason.empty());
  try {
    GpuNearestNeighbors gpu;
    FAIL() << "constructed without a GPU";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("GPU k-NN"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace gplanner
