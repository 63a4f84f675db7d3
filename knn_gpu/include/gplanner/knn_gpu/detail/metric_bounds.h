#pragma once
// Internals of the k-NN search, on host and device: lower bounds of the configuration
// metric over boxes of configurations (to skip whole tiles of candidates), the
// coordinates that order points along a space-filling curve, and the neighbour order.
// The CPU tests run exactly these functions; the GPU kernels call them.

#include <cmath>
#include <cstdint>

#include "gplanner/knn_gpu/configuration_metric.h"

namespace gplanner {
namespace detail {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kTwoPiF = 6.28318530717958647692f;

// The neighbour order: by distance, then by index (the deterministic tie rule).
GP_METRIC_HD bool neighbor_before(float distance_a, int index_a, float distance_b, int index_b) {
  return distance_a < distance_b || (distance_a == distance_b && index_a < index_b);
}

// Whether candidates whose metric is bounded below by `lower_bound` can be skipped by a
// search whose current cut-off is `threshold` (its k-th distance, or the radius). The
// bounds are computed in float along different paths than configuration_distance() (and
// acos is not exactly monotone), so a small relative and absolute slack keeps ties safe.
GP_METRIC_HD float prune_limit(float threshold) { return threshold * 1.00001f + 1e-6f; }
GP_METRIC_HD bool prunable(float lower_bound, float threshold) {
  return lower_bound > prune_limit(threshold);
}

// An angle wrapped into [-pi, pi].
GP_METRIC_HD float wrap_angle(float a) { return a - kTwoPiF * std::rint(a / kTwoPiF); }

// Whether coordinate c of a configuration row is an angle that wraps (a planar base's
// heading or a continuous joint).
GP_METRIC_HD bool wraps(const ConfigurationMetric& m, int c) {
  if (m.base == MetricBase::kPlanar && c == 2) return true;
  const int joint = c - m.base_width();
  return joint >= 0 && m.continuous(joint);
}

// Coordinate c of configuration q (shape [m.width()]) as tile boxes store it: a floating
// base's quaternion flipped to w >= 0 (q and -q are one rotation), wrapping angles in
// [-pi, pi], everything else as is.
GP_METRIC_HD float box_coordinate(const ConfigurationMetric& m, const float* q, int c) {
  if (m.base == MetricBase::kFloating && c >= 3 && c < 7) return q[3] < 0 ? -q[c] : q[c];
  return wraps(m, c) ? wrap_angle(q[c]) : q[c];
}

// The distance from x to the interval [lo, hi]; 0 inside.
GP_METRIC_HD float interval_gap(float x, float lo, float hi) {
  return std::fmax(std::fmax(lo - x, x - hi), 0.0f);
}

// The distance between the intervals [lo_a, hi_a] and [lo_b, hi_b]; 0 where they meet.
GP_METRIC_HD float interval_interval_gap(float lo_a, float hi_a, float lo_b, float hi_b) {
  return std::fmax(std::fmax(lo_b - hi_a, lo_a - hi_b), 0.0f);
}

// The angular distance (as angle_difference) from angle a to the arc [lo, hi], a
// sub-interval of [-pi, pi]; 0 inside.
GP_METRIC_HD float arc_gap(float a, float lo, float hi) {
  const float w = wrap_angle(a);
  if (w >= lo && w <= hi) return 0;
  return std::fmin(angle_difference(a, lo), angle_difference(a, hi));
}

// The angular distance between two arcs [lo_a, hi_a] and [lo_b, hi_b] in [-pi, pi]: 0
// where they meet, else the nearest pair of end points.
GP_METRIC_HD float arc_arc_gap(float lo_a, float hi_a, float lo_b, float hi_b) {
  if (lo_a <= hi_b && lo_b <= hi_a) return 0;
  return std::fmin(std::fmin(angle_difference(lo_a, lo_b), angle_difference(lo_a, hi_b)),
                   std::fmin(angle_difference(hi_a, lo_b), angle_difference(hi_a, hi_b)));
}

// sqrt, approximated on the device (one MUFU instruction, relative error ~1e-7: the
// bounds using it are compared through prunable(), whose slack covers that).
GP_METRIC_HD float approximate_sqrt(float x) {
#ifdef __CUDA_ARCH__
  float root;
  asm("sqrt.approx.f32 %0, %1;" : "=f"(root) : "f"(x));
  return root;
#else
  return std::sqrt(x);
#endif
}

// a * b + c, fused on the device (for bounds only: configuration_distance() is compiled
// without fused multiply-adds so that it rounds as on the host).
GP_METRIC_HD float multiply_add(float a, float b, float c) {
#ifdef __CUDA_ARCH__
  return __fmaf_rn(a, b, c);
#else
  return a * b + c;
#endif
}

// A lower bound of the rotation angle 2 acos(x) for an upper bound x of |qa . qb|, without
// acos: 2 acos(x) >= 2 sqrt(2 (1 - x)) on [0, 1], since cos y >= 1 - y^2 / 2 (at most
// 1.5% below the angle up to 1.2 rad). The bound is raised by a few ulps near 1, where
// rounding matters most.
GP_METRIC_HD float angle_for_dot_bound(float dot_bound) {
  const float x = std::fmin(dot_bound + 1e-6f, 1.0f);
  return 2.0f * approximate_sqrt(multiply_add(-2.0f, x, 2.0f));
}

// A lower bound of quaternion_angle(q, p) over unit quaternions p in the box [lo, hi]
// (box coordinates, shape [4] each); q (shape [4]) of either sign.
GP_METRIC_HD float quaternion_box_angle_bound(const float* q, const float* lo, const float* hi) {
  float dot_max = 0, dot_min = 0;
  for (int i = 0; i < 4; ++i) {
    const float a = q[i] * lo[i], b = q[i] * hi[i];
    dot_max += std::fmax(a, b);
    dot_min += std::fmin(a, b);
  }
  return angle_for_dot_bound(std::fmax(dot_max, -dot_min));
}

// A lower bound of quaternion_angle(q, p) over q in the box [lo_a, hi_a] and p in the box
// [lo_b, hi_b] (box coordinates, shape [4] each).
GP_METRIC_HD float quaternion_box_box_angle_bound(const float* lo_a, const float* hi_a,
                                                  const float* lo_b, const float* hi_b) {
  float dot_max = 0, dot_min = 0;
  for (int i = 0; i < 4; ++i) {
    const float c0 = lo_a[i] * lo_b[i], c1 = lo_a[i] * hi_b[i];
    const float c2 = hi_a[i] * lo_b[i], c3 = hi_a[i] * hi_b[i];
    dot_max += std::fmax(std::fmax(c0, c1), std::fmax(c2, c3));
    dot_min += std::fmin(std::fmin(c0, c1), std::fmin(c2, c3));
  }
  return angle_for_dot_bound(std::fmax(dot_max, -dot_min));
}

// A cheap lower bound of configuration_distance(m, a, b) for a floating base (the joints
// count 0), without acos (see angle_for_dot_bound()). Lets the search skip most exact
// distances.
GP_METRIC_HD float floating_base_lower_bound(const ConfigurationMetric& m, const float* a,
                                             const float* b) {
  const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  const float dot = std::fabs(
      multiply_add(a[6], b[6], multiply_add(a[5], b[5], multiply_add(a[4], b[4], a[3] * b[3]))));
  const float position = approximate_sqrt(multiply_add(dz, dz, multiply_add(dy, dy, dx * dx)));
  return multiply_add(m.position_weight, position, m.rotation_weight * angle_for_dot_bound(dot));
}

// A lower bound of configuration_distance(m, q, p) over all configurations p whose box
// coordinates lie in [lo, hi] (each shape [m.width()]); q: shape [m.width()]. Follows
// configuration_distance() term by term, each term bounded below.
GP_METRIC_HD float point_box_lower_bound(const ConfigurationMetric& m, const float* q,
                                         const float* lo, const float* hi) {
  float base_term = 0;
  if (m.base == MetricBase::kFloating) {
    const float gx = interval_gap(q[0], lo[0], hi[0]), gy = interval_gap(q[1], lo[1], hi[1]),
                gz = interval_gap(q[2], lo[2], hi[2]);
    base_term = m.position_weight * approximate_sqrt(gx * gx + gy * gy + gz * gz) +
                m.rotation_weight * quaternion_box_angle_bound(q + 3, lo + 3, hi + 3);
  } else if (m.base == MetricBase::kPlanar) {
    const float gx = interval_gap(q[0], lo[0], hi[0]), gy = interval_gap(q[1], lo[1], hi[1]);
    base_term = m.position_weight * approximate_sqrt(gx * gx + gy * gy) +
                m.rotation_weight * arc_gap(q[2], lo[2], hi[2]);
  }
  const int offset = m.base_width();
  float joints = 0;
  for (int j = 0; j < m.joint_count; ++j) {
    const int c = offset + j;
    joints += m.continuous(j) ? arc_gap(q[c], lo[c], hi[c]) : interval_gap(q[c], lo[c], hi[c]);
  }
  return base_term + m.joint_weight * joints;
}

// A lower bound of configuration_distance(m, q, p) over q in the box [lo_a, hi_a] and p in
// the box [lo_b, hi_b] (box coordinates, each shape [m.width()]).
GP_METRIC_HD float box_box_lower_bound(const ConfigurationMetric& m, const float* lo_a,
                                       const float* hi_a, const float* lo_b, const float* hi_b) {
  float base_term = 0;
  if (m.base == MetricBase::kFloating || m.base == MetricBase::kPlanar) {
    const int dims = m.base == MetricBase::kFloating ? 3 : 2;
    float g2 = 0;
    for (int i = 0; i < dims; ++i) {
      const float g = interval_interval_gap(lo_a[i], hi_a[i], lo_b[i], hi_b[i]);
      g2 += g * g;
    }
    const float rotation =
        m.base == MetricBase::kFloating
            ? quaternion_box_box_angle_bound(lo_a + 3, hi_a + 3, lo_b + 3, hi_b + 3)
            : arc_arc_gap(lo_a[2], hi_a[2], lo_b[2], hi_b[2]);
    base_term = m.position_weight * approximate_sqrt(g2) + m.rotation_weight * rotation;
  }
  const int offset = m.base_width();
  float joints = 0;
  for (int j = 0; j < m.joint_count; ++j) {
    const int c = offset + j;
    joints += m.continuous(j) ? arc_arc_gap(lo_a[c], hi_a[c], lo_b[c], hi_b[c])
                              : interval_interval_gap(lo_a[c], hi_a[c], lo_b[c], hi_b[c]);
  }
  return base_term + m.joint_weight * joints;
}

// ---------------------------------------------------------------- sort embedding

// Points are ordered along a Morton curve through a few "embedding" coordinates, in which
// Euclidean closeness approximates the metric: weighted base position, 2 x rotation
// weight x the quaternion's vector part (w >= 0), a planar heading and continuous joints
// as weighted (cos, sin), other joints weighted. Two slots per joint (the second is 0 for
// joints that do not wrap) keep the layout fixed. Only the order depends on it: every
// bound above holds for any order.
GP_METRIC_HD int embedding_width(const ConfigurationMetric& m) {
  const int base = m.base == MetricBase::kFloating ? 6 : m.base == MetricBase::kPlanar ? 4 : 0;
  return base + 2 * m.joint_count;
}

// Embedding coordinate e (in [0, embedding_width(m))) of configuration q.
GP_METRIC_HD float embedding_coordinate(const ConfigurationMetric& m, const float* q, int e) {
  int joint_slot = e;
  if (m.base == MetricBase::kFloating) {
    if (e < 3) return m.position_weight * q[e];
    if (e < 6) return 2.0f * m.rotation_weight * (q[3] < 0 ? -q[e + 1] : q[e + 1]);
    joint_slot = e - 6;
  } else if (m.base == MetricBase::kPlanar) {
    if (e < 2) return m.position_weight * q[e];
    if (e == 2) return m.rotation_weight * std::cos(q[2]);
    if (e == 3) return m.rotation_weight * std::sin(q[2]);
    joint_slot = e - 4;
  }
  const int joint = joint_slot / 2;
  const float x = q[m.base_width() + joint];
  if (m.continuous(joint)) {
    return m.joint_weight * (joint_slot % 2 == 0 ? std::cos(x) : std::sin(x));
  }
  return joint_slot % 2 == 0 ? m.joint_weight * x : 0.0f;
}

// The most embedding coordinates a Morton code interleaves.
constexpr int kMaxMortonAxes = 6;

// The Morton code of quantised coordinates cells (shape [axes], each < 2^bits), most
// significant bit first, axis 0 leading; axes * bits <= 63.
GP_METRIC_HD std::uint64_t morton_code(const std::uint32_t* cells, int axes, int bits) {
  std::uint64_t code = 0;
  for (int b = bits - 1; b >= 0; --b) {
    for (int a = 0; a < axes; ++a) code = (code << 1) | ((cells[a] >> b) & 1u);
  }
  return code;
}

}  // namespace detail
}  // namespace gplanner
