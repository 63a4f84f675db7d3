// NearestNodeIndex against the plain scan it replaces: every node's configuration_distance
// in order, the first of the least kept, removed nodes passed over; on an arm's metric
// (the nodes by columns) and on metrics that go row by row.

#include "gplanner/planner/planning/nearest_node_index.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace gplanner {
namespace {

std::int32_t scan(const ConfigurationMetric& m, const std::vector<float>& nodes,
                  const std::vector<std::uint8_t>& removed, const float* q) {
  const int width = m.width();
  std::int32_t best = -1;
  float best_distance = 0;
  for (std::size_t i = 0; i < removed.size(); ++i) {
    if (removed[i]) continue;
    const float d = configuration_distance(m, &nodes[i * width], q);
    if (best < 0 || d < best_distance) {
      best = static_cast<std::int32_t>(i);
      best_distance = d;
    }
  }
  return best;
}

ConfigurationMetric arm(int joints, std::uint64_t continuous = 0) {
  ConfigurationMetric m;
  m.joint_count = joints;
  m.joint_weight = 0.7f;
  m.continuous_mask = continuous;
  return m;
}

// Nodes on a coarse grid (many ties, duplicates) and uniform ones, a tenth removed; each
// query's answer the scan's as the nodes come.
void expect_scan_answers(const ConfigurationMetric& m, unsigned seed) {
  const int width = m.width();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(-3.0f, 3.0f);
  std::uniform_int_distribution<int> grid(-2, 2);
  NearestNodeIndex index(m);
  std::vector<float> nodes;
  std::vector<std::uint8_t> removed;
  std::vector<float> q(width);
  auto draw = [&](float* row, bool on_grid) {
    for (int k = 0; k < width; ++k) row[k] = on_grid ? 0.5f * grid(rng) : uniform(rng);
    if (m.base == MetricBase::kFloating) {  // a unit quaternion
      float n = 0;
      for (int k = 3; k < 7; ++k) n += row[k] * row[k];
      for (int k = 3; k < 7; ++k) row[k] = n > 0 ? row[k] / std::sqrt(n) : (k == 3 ? 1.0f : 0.0f);
    }
  };
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    std::vector<float> row(width);
    draw(row.data(), i % 2 == 0);
    nodes.insert(nodes.end(), row.begin(), row.end());
    removed.push_back(i % 10 == 3);
    index.add(row.data());
    ASSERT_EQ(index.size(), removed.size());
    if (i % 97 != 0 && i < 2990) continue;
    for (int t = 0; t < 8; ++t) {
      draw(q.data(), t % 2 == 0);
      const std::int32_t got = index.nearest(
          nodes.data(), q.data(), [&](std::int32_t n) { return removed[n] != 0; },
          [] { return false; });
      ASSERT_EQ(got, scan(m, nodes, removed, q.data())) << "after " << i + 1 << " nodes";
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  index.clear();
  EXPECT_EQ(index.size(), 0u);
  EXPECT_EQ(index.nearest(
                nodes.data(), q.data(), [](std::int32_t) { return false; }, [] { return false; }),
            -1);
}

TEST(NearestNodeIndex, AnArmsNodesByColumnsGiveTheScansAnswers) {
  expect_scan_answers(arm(7), 1);
  expect_scan_answers(arm(1), 2);
  expect_scan_answers(arm(38), 3);
}

TEST(NearestNodeIndex, WrappingJointsAndBasesGoRowByRowWithTheSameAnswers) {
  expect_scan_answers(arm(7, 0b1000100), 4);
  ConfigurationMetric planar = arm(3);
  planar.base = MetricBase::kPlanar;
  planar.position_weight = 2;
  expect_scan_answers(planar, 5);
  ConfigurationMetric floating = arm(0);
  floating.base = MetricBase::kFloating;
  floating.rotation_weight = 0.3f;
  expect_scan_answers(floating, 6);
}

TEST(NearestNodeIndex, EveryNodeRemovedOrAStopGivesNone) {
  const ConfigurationMetric m = arm(7);
  NearestNodeIndex index(m);
  std::vector<float> nodes;
  const std::size_t count = 3 * NearestNodeIndex::kPollNodes;
  for (std::size_t i = 0; i < count; ++i) {
    const std::vector<float> row(7, 0.001f * static_cast<float>(i));
    nodes.insert(nodes.end(), row.begin(), row.end());
    index.add(row.data());
  }
  const std::vector<float> q(7, 1000.0f);  // beyond the last node
  EXPECT_EQ(index.nearest(
                nodes.data(), q.data(), [](std::int32_t) { return true; }, [] { return false; }),
            -1);
  EXPECT_EQ(index.nearest(
                nodes.data(), q.data(), [](std::int32_t) { return false; }, [] { return false; }),
            static_cast<std::int32_t>(count - 1));
  int polls = 0;
  EXPECT_EQ(
      index.nearest(
          nodes.data(), q.data(), [](std::int32_t) { return false; }, [&] { return ++polls == 2; }),
      -1);
  EXPECT_EQ(polls, 2);
}

}  // namespace
}  // namespace gplanner
