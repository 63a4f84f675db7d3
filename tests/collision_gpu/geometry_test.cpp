// The geometry core against FCL's own implementations (double) on seeded random
// inputs, for float and double.

#include <fcl/math/bv/OBB.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "gplanner/collision_gpu/geometry/obb.h"
#include "gplanner/collision_gpu/geometry/triangle_distance.h"

namespace gplanner::geometry {
namespace {

template <typename T>
Vec3<T> to_vec3(const Eigen::Vector3d& p) {
  return {T(p.x()), T(p.y()), T(p.z())};
}

template <typename T>
Mat3<T> to_mat3(const Eigen::Matrix3d& m) {
  Mat3<T> out;
  for (int i = 0; i < 3; ++i) out.r[i] = {T(m(i, 0)), T(m(i, 1)), T(m(i, 2))};
  return out;
}

struct TrianglePair {
  Eigen::Vector3d a[3], b[3];
};

double fcl_distance(const TrianglePair& pair) {
  Eigen::Vector3d p, q;
  return fcl::detail::TriangleDistance<double>::triDistance(pair.a, pair.b, p, q);
}

// Moves b so that the pair is exactly `target` apart (along the closest-point
// direction: the distance falls at rate one and no other pair can get closer).
TrianglePair at_distance(TrianglePair pair, double target) {
  Eigen::Vector3d p, q;
  const double d = fcl::detail::TriangleDistance<double>::triDistance(pair.a, pair.b, p, q);
  const Eigen::Vector3d shift = (p - q).normalized() * (d - target);
  for (auto& v : pair.b) v += shift;
  return pair;
}

template <typename T>
bool within(const TrianglePair& pair, double threshold) {
  const Vec3<T> a[3] = {to_vec3<T>(pair.a[0]), to_vec3<T>(pair.a[1]), to_vec3<T>(pair.a[2])};
  const Vec3<T> b[3] = {to_vec3<T>(pair.b[0]), to_vec3<T>(pair.b[1]), to_vec3<T>(pair.b[2])};
  return triangles_within(a, b, T(threshold));
}

// Random pairs of every shape: general, slivers, degenerate (collinear, a point),
// coplanar, sharing a vertex.
TrianglePair random_pair(std::mt19937_64* rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  auto point = [&] { return Eigen::Vector3d(u(*rng), u(*rng), u(*rng)); };
  TrianglePair pair;
  for (auto& v : pair.a) v = point();
  for (auto& v : pair.b) v = point() + Eigen::Vector3d(0.5, 0, 0);
  switch ((*rng)() % 6) {
    case 0:
      pair.a[2] = pair.a[0] + 1e-4 * (pair.a[1] - pair.a[0]) + 1e-6 * point();
      break;  // sliver
    case 1:
      pair.b[2] = 0.5 * (pair.b[0] + pair.b[1]);
      break;  // collinear
    case 2:
      pair.b[1] = pair.b[2] = pair.b[0];
      break;  // a point
    case 3:
      for (auto& v : pair.b) v.z() = 0;
      for (auto& v : pair.a) v.z() = 0;
      break;  // coplanar
    case 4:
      pair.b[0] = pair.a[1];
      break;  // shared vertex
    default:
      break;
  }
  return pair;
}

// Never reports apart what is within 0.9 threshold; reports within what is beyond 1.1
// threshold in at most `allowed_false_alarms` of the cases (float keeps slivers,
// whose plane it cannot resolve, as their edges grown by the sliver's thickness).
template <typename T>
void agrees_with_fcl_on_distance(double threshold, double allowed_false_alarms) {
  std::mt19937_64 rng(42);
  int checked = 0, far = 0, false_alarms = 0;
  for (int i = 0; i < 20000; ++i) {
    const TrianglePair pair = random_pair(&rng);
    const double d = fcl_distance(pair);
    if (d < 1e-9) {
      ASSERT_TRUE(within<T>(pair, threshold)) << "intersecting pair " << i << " reported apart";
      ++checked;
      continue;
    }
    for (const double factor : {0.0, 0.5, 0.9, 1.1, 2.0, 10.0}) {
      const TrianglePair moved = at_distance(pair, factor * threshold);
      const double actual = fcl_distance(moved);
      if (actual <= 0.9 * threshold) {
        ASSERT_TRUE(within<T>(moved, threshold))
            << "pair " << i << " at " << actual << " reported apart";
      } else if (actual >= 1.1 * threshold) {
        ++far;
        const bool alarm = within<T>(moved, threshold);
        false_alarms += alarm;
        if (allowed_false_alarms == 0)
          ASSERT_FALSE(alarm) << "pair " << i << " at " << actual << " reported within";
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 50000);
  EXPECT_LE(false_alarms, allowed_false_alarms * far) << false_alarms << " of " << far;
}

TEST(TriangleDistance, AgreesWithFclInDouble) { agrees_with_fcl_on_distance<double>(1e-3, 0); }
TEST(TriangleDistance, AgreesWithFclInDoubleAtSmallThresholds) {
  agrees_with_fcl_on_distance<double>(2e-5, 0);
}
TEST(TriangleDistance, AgreesWithFclInFloat) { agrees_with_fcl_on_distance<float>(1e-3, 0); }
TEST(TriangleDistance, FloatNeverMissesAtSmallThresholds) {
  agrees_with_fcl_on_distance<float>(2e-5, 0.01);
}

// The float plane test used before the double leaf test never rejects a pair within
// the threshold, and rejects most pairs well beyond it.
TEST(TriangleDistance, FloatPlaneRejectionIsConservative) {
  std::mt19937_64 rng(77);
  const double threshold = 2e-5;
  int far = 0, rejected_far = 0;
  for (int i = 0; i < 20000; ++i) {
    const TrianglePair pair = random_pair(&rng);
    if (fcl_distance(pair) < 1e-9) continue;
    for (const double factor : {0.0, 0.5, 0.99, 2.0, 100.0, 1e4}) {
      const TrianglePair moved = at_distance(pair, factor * threshold);
      Vec3<float> a[3], b[3];
      for (int k = 0; k < 3; ++k) {
        a[k] = to_vec3<float>(moved.a[k]);
        b[k] = to_vec3<float>(moved.b[k]);
      }
      const bool rejected = beyond_plane(b, a[0], triangle_plane(a), float(threshold)) ||
                            beyond_plane(a, b[0], triangle_plane(b), float(threshold));
      if (fcl_distance(moved) <= threshold) {
        ASSERT_FALSE(rejected) << "pair " << i << " within the threshold rejected";
      } else if (factor >= 100) {
        ++far;
        rejected_far += rejected;
      }
    }
  }
  EXPECT_GT(rejected_far, far / 4) << rejected_far << " of " << far;
}

// The float edge-axis test (the nine axes across an edge of each triangle, used after
// the face planes) never rejects a pair within the threshold, at every scale, and
// rejects most of the pairs well beyond it that the planes leave (not those with a
// triangle shrunk to a point, whose edges give no axis).
TEST(TriangleDistance, FloatEdgeAxisRejectionIsConservative) {
  std::mt19937_64 rng(78);
  int far = 0, by_planes_far = 0, rejected_far = 0, near = 0;
  for (const double scale : {1e-3, 1.0, 1e3}) {
    const double threshold = 2e-5 * scale;
    for (int i = 0; i < 20000; ++i) {
      TrianglePair pair = random_pair(&rng);
      for (auto* t : {pair.a, pair.b})
        for (int k = 0; k < 3; ++k) t[k] *= scale;
      if (fcl_distance(pair) < 1e-9 * scale) continue;
      for (const double factor : {0.0, 0.5, 0.99, 2.0, 100.0, 1e4}) {
        const TrianglePair moved = at_distance(pair, factor * threshold);
        Vec3<float> a[3], b[3];
        TrianglePair rounded;  // the float triangles, exactly, for FCL
        for (int k = 0; k < 3; ++k) {
          a[k] = to_vec3<float>(moved.a[k]);
          b[k] = to_vec3<float>(moved.b[k]);
          rounded.a[k] = Eigen::Vector3d(a[k].x, a[k].y, a[k].z);
          rounded.b[k] = Eigen::Vector3d(b[k].x, b[k].y, b[k].z);
        }
        const bool by_edges = beyond_edge_axes(a, b, float(threshold));
        if (fcl_distance(rounded) <= threshold) {
          ++near;
          ASSERT_FALSE(by_edges) << "pair " << i << " at scale " << scale
                                 << " within the threshold rejected";
        } else if (factor >= 100) {
          ++far;
          const bool by_planes = beyond_plane(b, a[0], triangle_plane(a), float(threshold)) ||
                                 beyond_plane(a, b[0], triangle_plane(b), float(threshold));
          by_planes_far += by_planes;
          rejected_far += by_planes || by_edges;
        }
      }
    }
  }
  EXPECT_GT(near, 50000);
  // The planes leave far - by_planes_far; the edge axes take most of those.
  EXPECT_GT(rejected_far - by_planes_far, 0.6 * (far - by_planes_far))
      << "planes " << by_planes_far << ", planes and edges " << rejected_far << " of " << far;
}

// The leaf test's inline max and min are std::fmax and std::fmin on every pair of special
// and ordinary values (a NaN gives the other argument, two give NaN), so that inlining
// them changes no verdict; only a zero's sign may differ, which no caller can see.
template <typename T>
void same_as_fmax_and_fmin() {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
  const T values[] = {nan, -inf, T(-2.5), T(-1e-30), T(-0.0), T(0.0), T(1e-30), T(3), inf};
  const auto same = [](T got, T want) {
    return (std::isnan(got) && std::isnan(want)) || (got == want);  // 0 == -0
  };
  for (const T a : values) {
    for (const T b : values) {
      EXPECT_TRUE(same(max_number(a, b), std::fmax(a, b))) << a << ", " << b;
      EXPECT_TRUE(same(min_number(a, b), std::fmin(a, b))) << a << ", " << b;
    }
  }
}

TEST(TriangleDistance, InlineMaxAndMinAreFmaxAndFmin) {
  same_as_fmax_and_fmin<float>();
  same_as_fmax_and_fmin<double>();
}

TEST(TriangleDistance, SegmentDistancesOnKnownCases) {
  const Vec3<double> o{0, 0, 0}, x{1, 0, 0};
  EXPECT_DOUBLE_EQ(
      segment_segment_squared_distance(o, x, Vec3<double>{0.5, 1, 0}, Vec3<double>{0.5, 2, 0}),
      1.0);
  EXPECT_DOUBLE_EQ(
      segment_segment_squared_distance(o, x, Vec3<double>{2, 0, 0}, Vec3<double>{3, 0, 0}),
      1.0);  // collinear
  EXPECT_DOUBLE_EQ(
      segment_segment_squared_distance(o, o, Vec3<double>{0, 3, 0}, Vec3<double>{0, 3, 0}),
      9.0);  // points
  EXPECT_DOUBLE_EQ(
      segment_segment_squared_distance(o, x, Vec3<double>{0.5, -1, 1}, Vec3<double>{0.5, 1, 1}),
      1.0);  // crossing above
}

Eigen::Matrix3d random_rotation(std::mt19937_64* rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(*rng), n(*rng), n(*rng), n(*rng)).normalized().toRotationMatrix();
}

TEST(ObbOverlap, AgreesWithFclAndIsNeverLessConservative) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.05, 1.0), c(-1.5, 1.5);
  int overlaps = 0, disagreements = 0;
  const int n = 50000;
  for (int i = 0; i < n; ++i) {
    fcl::OBB<double> a, b;
    a.axis = random_rotation(&rng);
    b.axis = random_rotation(&rng);
    a.To = Eigen::Vector3d(c(rng), c(rng), c(rng));
    b.To = Eigen::Vector3d(c(rng), c(rng), c(rng));
    a.extent = Eigen::Vector3d(u(rng), u(rng), u(rng));
    b.extent = Eigen::Vector3d(u(rng), u(rng), u(rng));
    const bool expected = a.overlap(b);
    for (const bool as_float : {false, true}) {
      bool actual;
      if (as_float) {
        actual = obbs_overlap(
            Obb<float>{to_vec3<float>(a.To), to_mat3<float>(a.axis), to_vec3<float>(a.extent)},
            Obb<float>{to_vec3<float>(b.To), to_mat3<float>(b.axis), to_vec3<float>(b.extent)},
            0.0f);
      } else {
        actual = obbs_overlap(
            Obb<double>{to_vec3<double>(a.To), to_mat3<double>(a.axis), to_vec3<double>(a.extent)},
            Obb<double>{to_vec3<double>(b.To), to_mat3<double>(b.axis), to_vec3<double>(b.extent)},
            0.0);
      }
      if (expected) ASSERT_TRUE(actual) << "box pair " << i << " overlaps in FCL";
      disagreements += actual != expected;
    }
    overlaps += expected;
  }
  EXPECT_GT(overlaps, n / 10);
  EXPECT_LT(overlaps, n * 9 / 10);
  EXPECT_LT(disagreements, n / 1000) << "only boxes within epsilon of touching may differ";
}

TEST(ObbOverlap, MarginGrowsBothBoxes) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Matrix3d R = random_rotation(&rng);
    const Eigen::Vector3d ea(0.3, 0.2, 0.1), eb(0.1, 0.4, 0.2);
    const double gap = 0.01;
    // B shares A's axes and sits `gap` beyond A's +x face.
    const Eigen::Vector3d cb = R * Eigen::Vector3d(ea.x() + eb.x() + gap, 0.05, -0.02);
    const Obb<double> a{{0, 0, 0}, to_mat3<double>(R), to_vec3<double>(ea)};
    const Obb<double> b{to_vec3<double>(cb), to_mat3<double>(R), to_vec3<double>(eb)};
    EXPECT_FALSE(obbs_overlap(a, b, 0.9 * gap));
    EXPECT_TRUE(obbs_overlap(a, b, 1.1 * gap));
    EXPECT_TRUE(sphere_overlaps_obb(to_vec3<double>(R * Eigen::Vector3d(0.3 + 0.5 * gap, 0, 0)),
                                    0.0, a, 0.6 * gap));
    EXPECT_FALSE(sphere_overlaps_obb(to_vec3<double>(R * Eigen::Vector3d(0.3 + 0.5 * gap, 0, 0)),
                                     0.0, a, 0.4 * gap));
  }
}

TEST(Transforms, ComposeInvertAndRotate) {
  const Mat3<double> R = axis_angle(Vec3<double>{0, 0, 1}, 3.14159265358979323846 / 2);
  const Vec3<double> p = R * Vec3<double>{1, 0, 0};
  EXPECT_NEAR(p.x, 0, 1e-15);
  EXPECT_NEAR(p.y, 1, 1e-15);
  const Transform<double> X{R, {1, 2, 3}};
  const Vec3<double> back = inverse(X) * (X * Vec3<double>{0.3, -0.2, 0.7});
  EXPECT_NEAR(back.x, 0.3, 1e-15);
  EXPECT_NEAR(back.z, 0.7, 1e-15);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const Mat3<double> Rq =
      quaternion_rotation(2 * q.w(), 2 * q.x(), 2 * q.y(), 2 * q.z());  // not unit
  const Eigen::Matrix3d expected = q.toRotationMatrix();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(Rq.r[i][j], expected(i, j), 1e-14);
  }
}

}  // namespace
}  // namespace gplanner::geometry
