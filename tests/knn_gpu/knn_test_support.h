#pragma once
// Shared by the k-NN tests: seeded random configurations for the three kinds of robot, the
// naive neighbour computation, and comparison of neighbour tables up to ties.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"

namespace gplanner::testing {

// A floating base (6 DOF) and `joints` joints, joint 1 continuous when there are two.
inline ConfigurationMetric floating_metric(int joints) {
  ConfigurationMetric m;
  m.base = MetricBase::kFloating;
  m.joint_count = joints;
  m.position_weight = 1.0f;
  m.rotation_weight = 0.7f;
  m.joint_weight = 0.3f;
  m.continuous_mask = joints > 1 ? 0b10u : 0u;
  return m;
}

// A planar base (x y theta) and a continuous joint 0 plus `joints - 1` others.
inline ConfigurationMetric planar_metric(int joints) {
  ConfigurationMetric m;
  m.base = MetricBase::kPlanar;
  m.joint_count = joints;
  m.position_weight = 1.0f;
  m.rotation_weight = 0.5f;
  m.joint_weight = 0.8f;
  m.continuous_mask = 0b1u;
  return m;
}

// `joints` joints, no base; joints 0 and 3 continuous.
inline ConfigurationMetric joints_metric(int joints) {
  ConfigurationMetric m;
  m.joint_count = joints;
  m.joint_weight = 1.0f;
  m.continuous_mask = 0b1001u;
  return m;
}

// A uniformly random unit quaternion (w x y z), by Shoemake's method.
template <typename Rng>
void random_quaternion(Rng& rng, float* q) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = u(rng), u3 = u(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1), two_pi = 6.283185307179586;
  q[0] = static_cast<float>(b * std::cos(two_pi * u3));
  q[1] = static_cast<float>(a * std::sin(two_pi * u2));
  q[2] = static_cast<float>(a * std::cos(two_pi * u2));
  q[3] = static_cast<float>(b * std::sin(two_pi * u3));
}

// n seeded random configurations for metric m, shape [n, m.width()]: base positions in a
// 4 x 3 x 2 m box, uniform rotations, headings and continuous joints over several turns
// (so wrap-around matters), other joints in [-2, 2]. Every 10th point repeats an earlier
// one, so that exact ties occur.
inline std::vector<float> random_configurations(const ConfigurationMetric& m, std::size_t n,
                                                unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const int width = m.width(), base = m.base_width();
  std::vector<float> points(n * width);
  for (std::size_t i = 0; i < n; ++i) {
    float* p = points.data() + i * width;
    if (i % 10 == 9) {
      const std::size_t earlier = static_cast<std::size_t>(unit(rng) * (i - 1));
      std::copy(points.begin() + earlier * width, points.begin() + (earlier + 1) * width, p);
      continue;
    }
    if (m.base == MetricBase::kFloating) {
      p[0] = 4 * unit(rng);
      p[1] = 3 * unit(rng);
      p[2] = 2 * unit(rng);
      random_quaternion(rng, p + 3);
    } else if (m.base == MetricBase::kPlanar) {
      p[0] = 4 * unit(rng);
      p[1] = 3 * unit(rng);
      p[2] = 12 * unit(rng) - 6;
    }
    for (int j = 0; j < m.joint_count; ++j)
      p[base + j] = m.continuous(j) ? 15 * unit(rng) - 7.5f : 4 * unit(rng) - 2;
  }
  return points;
}

// The naive answer: for each query, all distances sorted by (distance, index), cut at k.
// points: shape [n, width]; queries: shape [m, width], or nullptr for all points against
// each other (the point itself excluded).
inline NeighborTable naive_neighbors(const ConfigurationMetric& metric, const float* points,
                                     std::size_t n, const float* queries, std::size_t m, int k,
                                     float radius) {
  const std::size_t width = metric.width(), rows = queries ? m : n;
  NeighborTable table;
  table.k = k;
  table.rows = rows;
  table.indices.assign(rows * k, -1);
  table.distances.assign(rows * k, kUnboundedRadius);
  for (std::size_t i = 0; i < rows; ++i) {
    const float* q = queries ? queries + i * width : points + i * width;
    std::vector<std::pair<float, int>> all;
    for (std::size_t j = 0; j < n; ++j) {
      if (!queries && j == i) continue;
      const float d = configuration_distance(metric, q, points + j * width);
      if (d <= radius) all.emplace_back(d, static_cast<int>(j));
    }
    std::sort(all.begin(), all.end());
    for (std::size_t r = 0; r < all.size() && r < static_cast<std::size_t>(k); ++r) {
      table.distances[i * k + r] = all[r].first;
      table.indices[i * k + r] = all[r].second;
    }
  }
  return table;
}

// Exact equality of two tables, naming the first differing entry.
inline ::testing::AssertionResult same_tables(const NeighborTable& expected,
                                              const NeighborTable& actual) {
  if (expected.k != actual.k || expected.rows != actual.rows)
    return ::testing::AssertionFailure() << "shapes differ";
  for (std::size_t e = 0; e < expected.indices.size(); ++e) {
    if (expected.indices[e] != actual.indices[e] ||
        !(expected.distances[e] == actual.distances[e] ||
          (std::isinf(expected.distances[e]) && std::isinf(actual.distances[e])))) {
      return ::testing::AssertionFailure()
             << "row " << e / expected.k << " rank " << e % expected.k << ": expected "
             << expected.indices[e] << " at " << expected.distances[e] << ", got "
             << actual.indices[e] << " at " << actual.distances[e];
    }
  }
  return ::testing::AssertionSuccess();
}

// How far apart two float distances computed along different paths may be.
inline float distance_tolerance(float d) { return 1e-5f * d + 1e-5f; }

// Whether row `row` of two tables holds the same neighbours up to ties: equal distances
// rank by rank (within distance_tolerance), and any neighbour in one row but not the other
// lies at the row's last distance (or the radius) within that tolerance. Empty string when
// they agree, else what differs.
inline std::string row_difference(const NeighborTable& expected, const NeighborTable& actual,
                                  std::size_t row, float radius) {
  std::ostringstream out;
  const int ce = expected.count(row), ca = actual.count(row), k = expected.k;
  for (int r = 0; r < std::max(ce, ca); ++r) {
    if (r < ce && r < ca) {
      const float de = expected.distance(row, r), da = actual.distance(row, r);
      if (std::fabs(de - da) > distance_tolerance(de)) {
        out << "row " << row << " rank " << r << ": distance " << da << ", expected " << de;
        return out.str();
      }
    } else {
      const float d = r < ce ? expected.distance(row, r) : actual.distance(row, r);
      if (std::fabs(d - radius) > distance_tolerance(radius)) {
        out << "row " << row << ": " << ca << " neighbours, expected " << ce;
        return out.str();
      }
    }
  }
  if (ce == 0) return "";
  const float last = std::min(expected.distance(row, ce - 1),
                              ca > 0 ? actual.distance(row, ca - 1) : kUnboundedRadius);
  const int* e_begin = expected.indices.data() + row * k;
  const int* a_begin = actual.indices.data() + row * k;
  for (int r = 0; r < ce; ++r) {
    if (std::find(a_begin, a_begin + ca, e_begin[r]) == a_begin + ca &&
        expected.distance(row, r) < last - distance_tolerance(last)) {
      out << "row " << row << ": neighbour " << e_begin[r] << " at " << expected.distance(row, r)
          << " missing (last distance " << last << ")";
      return out.str();
    }
  }
  for (int r = 0; r < ca; ++r) {
    if (std::find(e_begin, e_begin + ce, a_begin[r]) == e_begin + ce &&
        actual.distance(row, r) < last - distance_tolerance(last)) {
      out << "row " << row << ": extra neighbour " << a_begin[r] << " at "
          << actual.distance(row, r) << " (last distance " << last << ")";
      return out.str();
    }
  }
  return "";
}

// Every row agrees up to ties (row_difference); reports the first few rows that do not.
inline ::testing::AssertionResult same_up_to_ties(const NeighborTable& expected,
                                                  const NeighborTable& actual,
                                                  float radius = kUnboundedRadius) {
  if (expected.k != actual.k || expected.rows != actual.rows)
    return ::testing::AssertionFailure() << "shapes differ";
  std::size_t bad = 0;
  std::ostringstream out;
  for (std::size_t row = 0; row < expected.rows; ++row) {
    const std::string difference = row_difference(expected, actual, row, radius);
    if (difference.empty()) continue;
    if (++bad <= 5) out << difference << "\n";
  }
  if (bad == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << bad << " of " << expected.rows << " rows differ:\n"
                                       << out.str();
}

}  // namespace gplanner::testing
