// The lower bounds that let the GPU search skip tiles: never above a distance to a point
// in the box, for every kind of robot, and the sort embedding's Morton code.

#include "gplanner/knn_gpu/detail/metric_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "knn_gpu/knn_test_support.h"

namespace gplanner {
namespace {

using detail::box_box_lower_bound;
using detail::box_coordinate;
using detail::point_box_lower_bound;
using detail::prunable;

// The box of rows [first, first + count) of points (shape [n, width]) in box coordinates;
// lo and hi: shape [width].
void tile_box(const ConfigurationMetric& m, const std::vector<float>& points, std::size_t first,
              std::size_t count, std::vector<float>* lo, std::vector<float>* hi) {
  const int width = m.width();
  lo->assign(width, INFINITY);
  hi->assign(width, -INFINITY);
  for (std::size_t i = first; i < first + count; ++i) {
    for (int c = 0; c < width; ++c) {
      const float x = box_coordinate(m, points.data() + i * width, c);
      (*lo)[c] = std::min((*lo)[c], x);
      (*hi)[c] = std::max((*hi)[c], x);
    }
  }
}

// Tiles of 32 points clustered around a random centre (small steps from it, so that boxes
// are tight and the bounds are tested where they bite), queries anywhere.
std::vector<float> clustered(const ConfigurationMetric& m, std::size_t tiles, float spread,
                             unsigned seed) {
  const int width = m.width();
  std::vector<float> centres = testing::random_configurations(m, tiles, seed);
  std::vector<float> points(tiles * 32 * width);
  std::mt19937 rng(seed + 1);
  std::normal_distribution<float> step(0.0f, spread);
  for (std::size_t t = 0; t < tiles; ++t) {
    for (int i = 0; i < 32; ++i) {
      float* p = points.data() + (t * 32 + i) * width;
      for (int c = 0; c < width; ++c) p[c] = centres[t * width + c] + step(rng);
      if (m.base == MetricBase::kFloating) {
        const float norm = std::sqrt(p[3] * p[3] + p[4] * p[4] + p[5] * p[5] + p[6] * p[6]);
        const float sign = i % 2 ? -1.0f : 1.0f;  // either sign of the same rotation
        for (int c = 3; c < 7; ++c) p[c] = sign * p[c] / norm;
      }
    }
  }
  return points;
}

class KnnBounds : public ::testing::TestWithParam<int> {
 protected:
  ConfigurationMetric metric() const {
    switch (GetParam()) {
      case 0:
        return testing::floating_metric(3);
      case 1:
        return testing::planar_metric(3);
      default:
        return testing::joints_metric(6);
    }
  }
};

TEST_P(KnnBounds, PointBoxBoundNeverExceedsADistance) {
  const ConfigurationMetric m = metric();
  const int width = m.width();
  const std::size_t tiles = 60;
  const std::vector<float> points = clustered(m, tiles, 0.05f, 20 + GetParam());
  const std::vector<float> queries = testing::random_configurations(m, 200, 30 + GetParam());
  std::vector<float> lo, hi;
  std::size_t positive = 0, checked = 0;
  for (std::size_t t = 0; t < tiles; ++t) {
    tile_box(m, points, t * 32, 32, &lo, &hi);
    for (std::size_t qi = 0; qi < 200 + 32; ++qi) {
      // Queries far away, and the tile's own points (bound 0 expected).
      const float* q =
          qi < 200 ? queries.data() + qi * width : points.data() + (t * 32 + qi - 200) * width;
      const float bound = point_box_lower_bound(m, q, lo.data(), hi.data());
      float nearest = INFINITY;
      for (int i = 0; i < 32; ++i)
        nearest =
            std::min(nearest, configuration_distance(m, q, points.data() + (t * 32 + i) * width));
      ASSERT_LE(bound, nearest) << "tile " << t << " query " << qi;
      ASSERT_FALSE(prunable(bound, nearest));
      if (qi >= 200) EXPECT_LE(bound, 1e-3f) << "a point of the tile itself";
      positive += bound > 0.5f * nearest;
      ++checked;
    }
  }
  EXPECT_GT(positive, checked / 4) << "the bound should usually be close to the distance";
}

TEST_P(KnnBounds, BoxBoxBoundNeverExceedsADistance) {
  const ConfigurationMetric m = metric();
  const int width = m.width();
  const std::size_t tiles = 40;
  const std::vector<float> points = clustered(m, tiles, 0.05f, 40 + GetParam());
  std::vector<float> lo_a, hi_a, lo_b, hi_b;
  std::size_t positive = 0, checked = 0;
  for (std::size_t a = 0; a < tiles; ++a) {
    tile_box(m, points, a * 32, 32, &lo_a, &hi_a);
    for (std::size_t b = 0; b < tiles; ++b) {
      tile_box(m, points, b * 32, 32, &lo_b, &hi_b);
      const float bound =
          box_box_lower_bound(m, lo_a.data(), hi_a.data(), lo_b.data(), hi_b.data());
      float nearest = INFINITY;
      for (int i = 0; i < 32; ++i) {
        for (int j = 0; j < 32; ++j) {
          nearest =
              std::min(nearest, configuration_distance(m, points.data() + (a * 32 + i) * width,
                                                       points.data() + (b * 32 + j) * width));
        }
      }
      ASSERT_LE(bound, nearest) << "tiles " << a << " and " << b;
      ASSERT_FALSE(prunable(bound, nearest));
      if (a == b) EXPECT_EQ(bound, 0.0f);
      positive += bound > 0.5f * nearest;
      ++checked;
    }
  }
  EXPECT_GT(positive, checked / 4);
}

INSTANTIATE_TEST_SUITE_P(Robots, KnnBounds, ::testing::Values(0, 1, 2),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(info.param == 0   ? "FloatingBase"
                                              : info.param == 1 ? "PlanarBase"
                                                                : "JointsOnly");
                         });

TEST(KnnBoundsFloating, BoundWithoutAcosNeverExceedsADistance) {
  // Random pairs, and pairs at small rotations (where acos is steep) and of either sign;
  // with joints (which the bound leaves out) and without (where it is tight).
  for (const int joints : {2, 0}) {
    const ConfigurationMetric m = testing::floating_metric(joints);
    const int width = m.width();
    const std::vector<float> points = testing::random_configurations(m, 2000, 50);
    const std::vector<float> near = clustered(m, 20, 1e-3f, 51);
    std::size_t tight = 0, checked = 0;
    auto check = [&](const float* a, const float* b, bool count) {
      const float bound = detail::floating_base_lower_bound(m, a, b);
      const float d = configuration_distance(m, a, b);
      ASSERT_FALSE(prunable(bound, d)) << bound << " above " << d;
      tight += count && bound >= 0.9f * d;
      checked += count;
    };
    for (std::size_t i = 0; i + 1 < 2000; i += 2)
      check(&points[i * width], &points[(i + 1) * width], true);
    // Near pairs: 1 - |dot| underflows float there, so the bound is sound but loose.
    for (std::size_t i = 0; i + 1 < 640; ++i)
      check(&near[i * width], &near[(i + 1) * width], false);
    if (joints == 0) EXPECT_EQ(tight, checked) << "2 sqrt(2 (1 - x)) >= 0.9 acos(x) on [0, 1]";
  }
}

TEST(KnnBoundsArcs, WrapAndArcGaps) {
  EXPECT_NEAR(detail::wrap_angle(7.0f), 7.0f - 6.2831853f, 1e-6);
  EXPECT_NEAR(detail::wrap_angle(-3.5f), -3.5f + 6.2831853f, 1e-6);
  // The arc [2.5, 3.1]: -3.1 lies 0.083 past its end the short way round.
  EXPECT_NEAR(detail::arc_gap(-3.1f, 2.5f, 3.1f), 6.2831853f - 6.2f, 1e-5);
  EXPECT_EQ(detail::arc_gap(2.8f + 6.2831853f, 2.5f, 3.1f), 0.0f);
  EXPECT_NEAR(detail::arc_gap(0.0f, 2.5f, 3.1f), 2.5f, 1e-6);
  // Arcs [2.5, 3.1] and [-3.1, -2.9] are 0.083 apart across +-pi.
  EXPECT_NEAR(detail::arc_arc_gap(2.5f, 3.1f, -3.1f, -2.9f), 6.2831853f - 6.2f, 1e-5);
  EXPECT_EQ(detail::arc_arc_gap(-1.0f, 1.0f, 0.5f, 2.0f), 0.0f);
}

TEST(KnnBoundsMorton, InterleavesAxesMostSignificantBitFirst) {
  const std::uint32_t cells[3] = {0b10, 0b01, 0b11};
  // bits of axis 0, 1, 2 at bit 1: 1 0 1; at bit 0: 0 1 1.
  EXPECT_EQ(detail::morton_code(cells, 3, 2), 0b101011u);
  const std::uint32_t one[1] = {5};
  EXPECT_EQ(detail::morton_code(one, 1, 21), 5u);
}

TEST(KnnBoundsEmbedding, SameRotationOfEitherSignEmbedsAlike) {
  const ConfigurationMetric m = testing::floating_metric(1);
  const float q[8] = {1, 2, 3, 0.5f, 0.5f, -0.5f, 0.5f, 0.25f};
  const float minus_q[8] = {1, 2, 3, -0.5f, -0.5f, 0.5f, -0.5f, 0.25f};
  ASSERT_EQ(detail::embedding_width(m), 8);
  for (int e = 0; e < 8; ++e) {
    EXPECT_EQ(detail::embedding_coordinate(m, q, e), detail::embedding_coordinate(m, minus_q, e));
  }
  EXPECT_EQ(detail::embedding_coordinate(m, q, 7), 0.0f) << "second slot of a plain joint";
}

}  // namespace
}  // namespace gplanner
