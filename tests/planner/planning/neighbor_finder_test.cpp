// The CPU neighbour finders (OMPL's GNAT for rigid bodies, brute force beyond 6 degrees
// of freedom) against knn_gpu's brute-force reference, called as the planner calls them:
// rounds of new points, each new point's k nearest among all so far; and the gpu
// backend's finder.

#include "gplanner/planner/planning/neighbor_finder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner {
namespace {

std::vector<float> random_points(const ConfigurationMetric& metric, std::size_t n,
                                 std::mt19937_64* rng) {
  std::uniform_real_distribution<float> position(0, 2), angle(-3.14159f, 3.14159f);
  std::normal_distribution<float> gauss;
  const int w = metric.width();
  std::vector<float> points(n * w);
  for (std::size_t i = 0; i < n; ++i) {
    float* q = &points[i * w];
    if (metric.base == MetricBase::kFloating) {
      for (int a = 0; a < 3; ++a) q[a] = position(*rng);
      float norm = 0;
      for (int a = 3; a < 7; ++a) norm += (q[a] = gauss(*rng)) * q[a];
      for (int a = 3; a < 7; ++a) q[a] /= std::sqrt(norm);
    } else if (metric.base == MetricBase::kPlanar) {
      q[0] = position(*rng);
      q[1] = position(*rng);
      q[2] = angle(*rng);
    }
    for (int j = 0; j < metric.joint_count; ++j) q[metric.base_width() + j] = angle(*rng);
  }
  return points;
}

// found (shape [n - first, k]) are the k nearest of points [first, n) among [0, n), up
// to ties: the j-th has the reference's j-th distance.
void expect_reference(const ConfigurationMetric& metric, const std::vector<float>& points,
                      std::size_t n, std::size_t first, int k, const std::vector<int>& found) {
  const int w = metric.width();
  ASSERT_EQ(found.size(), (n - first) * k);
  const NeighborTable reference = all_nearest_neighbors_cpu(metric, points.data(), n, k);
  for (std::size_t q = first; q < n; ++q) {
    for (int j = 0; j < k; ++j) {
      const int v = found[(q - first) * k + j];
      ASSERT_GE(v, 0) << q;
      ASSERT_LT(static_cast<std::size_t>(v), n);
      ASSERT_NE(static_cast<std::size_t>(v), q);
      const float expected = reference.distances[q * k + j];
      EXPECT_NEAR(configuration_distance(metric, &points[q * w], &points[v * w]), expected,
                  1e-5f * (1 + expected))
          << "point " << q << ", neighbour " << j;
    }
  }
}

void expect_finder_matches_reference(const ConfigurationMetric& metric) {
  const int k = 7;
  const std::size_t total = 1600;
  std::mt19937_64 rng(5);
  const std::vector<float> points = random_points(metric, total, &rng);
  std::unique_ptr<NeighborFinder> finder = make_neighbor_finder(metric, "cpu");
  EXPECT_EQ(finder->device(), "cpu");
  std::vector<int> found;
  for (std::size_t first = 0, n = 200; first < total; first = n, n = std::min(total, 2 * n)) {
    finder->nearest_of_new(points.data(), n, first, k, &found);
    expect_reference(metric, points, n, first, k, found);
  }
  // A call with fewer points than before starts afresh.
  finder->nearest_of_new(points.data(), 300, 0, k, &found);
  expect_reference(metric, points, 300, 0, k, found);
}

TEST(CpuNeighborFinder, RigidBodyMatchesTheReference) {  // 6 degrees of freedom: GNAT
  ConfigurationMetric metric;
  metric.base = MetricBase::kFloating;
  metric.rotation_weight = 0.5f;
  expect_finder_matches_reference(metric);
}

TEST(CpuNeighborFinder, PlanarBaseAndArmMatchTheReference) {  // 10: brute force
  ConfigurationMetric metric;
  metric.base = MetricBase::kPlanar;
  metric.joint_count = 7;
  metric.continuous_mask = 0b100;
  expect_finder_matches_reference(metric);
}

TEST(CpuNeighborFinder, ManyJointsMatchTheReference) {  // 38: brute force
  ConfigurationMetric metric;
  metric.joint_count = 38;
  metric.joint_weight = 2;
  expect_finder_matches_reference(metric);
}

// The gpu backend's finder, warmed up when made: rounds of a plan's sizes, one GPU call
// each, all as the reference says.
TEST(GpuNeighborFinder, MatchesTheReferenceRoundByRound) {
  std::string reason;
  if (!gpu_nearest_neighbors_available(&reason)) GTEST_SKIP() << "no GPU: " << reason;
  for (const MetricBase base : {MetricBase::kNone, MetricBase::kFloating}) {
    ConfigurationMetric metric;
    metric.base = base;
    metric.joint_count = base == MetricBase::kNone ? 7 : 0;
    const int k = 10;
    const std::size_t total = 8002;
    std::mt19937_64 rng(3);
    const std::vector<float> points = random_points(metric, total, &rng);
    std::unique_ptr<NeighborFinder> finder = make_neighbor_finder(metric, "gpu");
    ASSERT_EQ(finder->device(), "gpu");
    EXPECT_EQ(finder->device_calls(), 0u);  // the warm-up is not the planner's
    std::vector<int> found;
    const std::size_t ends[] = {2002, 4002, 8002};
    for (std::size_t r = 0, first = 0; r < 3; first = ends[r++]) {
      ASSERT_TRUE(finder->nearest_of_new(points.data(), ends[r], first, k, &found));
      expect_reference(metric, points, ends[r], first, k, found);
      EXPECT_EQ(finder->device_calls(), r + 1);
    }
  }
}

}  // namespace
}  // namespace gplanner
