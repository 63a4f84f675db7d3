#pragma once
// The broad phase's one pair rule for spheres, and the culling bounds that never drop a
// pair it accepts: the same code on the host and on the device, so that every broad-phase
// method (CPU or GPU, all pairs, sweep or grid) returns exactly the same pair set.

#include <cmath>

#include "gplanner/collision_gpu/geometry/host_device.h"

namespace gplanner::geometry {

namespace detail {
// Each operation rounded on its own: no fused multiply-add on the device (nvcc would
// contract a * b + c), none on the host either (ISO C++ mode: -ffp-contract=off).
GP_HD float sub_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fsub_rn(a, b);
#else
  return a - b;
#endif
}
GP_HD float add_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fadd_rn(a, b);
#else
  return a + b;
#endif
}
GP_HD float mul_rn(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fmul_rn(a, b);
#else
  return a * b;
#endif
}
// `value` rounded to a float not above it (down) or not below it (up).
GP_HD float float_down(double value) {
#if defined(__CUDA_ARCH__)
  return __double2float_rd(value);
#else
  const float f = static_cast<float>(value);
  return static_cast<double>(f) > value ? std::nextafter(f, -INFINITY) : f;
#endif
}
GP_HD float float_up(double value) {
#if defined(__CUDA_ARCH__)
  return __double2float_ru(value);
#else
  const float f = static_cast<float>(value);
  return static_cast<double>(f) < value ? std::nextafter(f, INFINITY) : f;
#endif
}
}  // namespace detail

// Spheres (c_a, r_a) and (c_b, r_b) overlap, touching included, when
// |c_a - c_b|^2 <= (r_a + r_b)^2, evaluated in float as ((dx dx + dy dy) + dz dz) <= s s,
// every operation rounded on its own. Symmetric: fl(a - b) = -fl(b - a).
GP_HD bool spheres_overlap(float ax, float ay, float az, float ar, float bx, float by, float bz,
                           float br) {
  using detail::add_rn;
  using detail::mul_rn;
  using detail::sub_rn;
  const float dx = sub_rn(ax, bx), dy = sub_rn(ay, by), dz = sub_rn(az, bz);
  const float d2 = add_rn(add_rn(mul_rn(dx, dx), mul_rn(dy, dy)), mul_rn(dz, dz));
  const float s = add_rn(ar, br);
  return d2 <= mul_rn(s, s);
}

// A pair the rule accepts has |c_a - c_b| <= (r_a + r_b)(1 + 4 2^-24) along every axis
// (each rounding is relative), so radii widened by kCullSlack cover it; kCullFloor (in
// length units, each side) covers squares that underflow (|d| below about 1e-22).
inline constexpr double kCullSlack = 1e-6;
inline constexpr double kCullFloor = 1e-20;

// The interval [lo, hi] a sphere covers along one axis, widened by kCullSlack and rounded
// outwards: a pair the rule accepts always has lo_b <= hi_a and lo_a <= hi_b.
GP_HD float cull_low(float center, float radius) {
  return detail::float_down(double(center) - (double(radius) * (1 + kCullSlack) + kCullFloor));
}
GP_HD float cull_high(float center, float radius) {
  return detail::float_up(double(center) + (double(radius) * (1 + kCullSlack) + kCullFloor));
}

}  // namespace gplanner::geometry
