#pragma once
// The planner's distance between two configurations, on host and device: a weighted sum
// of the base's position distance, the base's rotation angle, and the joints' absolute
// differences (the shorter way round for continuous joints). A configuration row is
// the base pose first (floating: x y z qw qx qy qz; planar: x y theta; none), then one
// float per joint.

#include <cmath>
#include <cstdint>

#ifdef __CUDACC__
#define GP_METRIC_HD __host__ __device__ inline
#else
#define GP_METRIC_HD inline
#endif

namespace gplanner {

enum class MetricBase : std::int32_t { kNone = 0, kPlanar = 1, kFloating = 2 };

// Joints beyond this many cannot be marked continuous (continuous_mask is 64 bits).
constexpr int kMaxContinuousJointIndex = 64;

struct ConfigurationMetric {
  MetricBase base = MetricBase::kNone;
  std::int32_t joint_count = 0;
  float position_weight = 1;          // per metre of base translation
  float rotation_weight = 1;          // per radian of base rotation angle
  float joint_weight = 1;             // per radian (or metre) of joint motion
  std::uint64_t continuous_mask = 0;  // bit j set: joint j wraps at +-pi

  GP_METRIC_HD int base_width() const {
    return base == MetricBase::kFloating ? 7 : base == MetricBase::kPlanar ? 3 : 0;
  }
  GP_METRIC_HD int width() const { return base_width() + joint_count; }
  GP_METRIC_HD bool continuous(int joint) const {
    return joint < kMaxContinuousJointIndex && ((continuous_mask >> joint) & 1u);
  }
};

// |a - b| for an angle, the shorter way round: in [0, pi].
GP_METRIC_HD float angle_difference(float a, float b) {
  const float kTwoPi = 6.28318530717958647692f;
  float d = std::fabs(a - b);
  d = std::fmod(d, kTwoPi);
  return d > kTwoPi - d ? kTwoPi - d : d;
}

// The rotation angle (in [0, pi]) between two unit quaternions w x y z.
GP_METRIC_HD float quaternion_angle(const float* qa, const float* qb) {
  float dot = std::fabs(qa[0] * qb[0] + qa[1] * qb[1] + qa[2] * qb[2] + qa[3] * qb[3]);
  dot = dot > 1.0f ? 1.0f : dot;
  return 2.0f * std::acos(dot);
}

// Distance between configurations a and b (each shape: [m.width()]).
GP_METRIC_HD float configuration_distance(const ConfigurationMetric& m, const float* a,
                                          const float* b) {
  float base_term = 0;
  if (m.base == MetricBase::kFloating) {
    const float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    base_term = m.position_weight * std::sqrt(dx * dx + dy * dy + dz * dz) +
                m.rotation_weight * quaternion_angle(a + 3, b + 3);
  } else if (m.base == MetricBase::kPlanar) {
    const float dx = a[0] - b[0], dy = a[1] - b[1];
    base_term = m.position_weight * std::sqrt(dx * dx + dy * dy) +
                m.rotation_weight * angle_difference(a[2], b[2]);
  }
  const int offset = m.base_width();
  float joints = 0;
  for (int j = 0; j < m.joint_count; ++j) {
    const float x = a[offset + j], y = b[offset + j];
    joints += m.continuous(j) ? angle_difference(x, y) : std::fabs(x - y);
  }
  return base_term + m.joint_weight * joints;
}

}  // namespace gplanner
