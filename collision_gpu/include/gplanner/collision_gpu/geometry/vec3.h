#pragma once
// Small fixed-size vector, rotation and rigid transform types, templated on the scalar
// (float on the GPU and in the CPU backend, double for references in tests).

#include <cmath>

#include "gplanner/collision_gpu/geometry/host_device.h"

namespace gplanner::geometry {

template <typename T>
struct Vec3 {
  T x, y, z;
  GP_HD T operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

template <typename T>
GP_HD Vec3<T> make_vec3(T x, T y, T z) {
  return Vec3<T>{x, y, z};
}
template <typename T>
GP_HD Vec3<T> operator+(Vec3<T> a, Vec3<T> b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <typename T>
GP_HD Vec3<T> operator-(Vec3<T> a, Vec3<T> b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <typename T>
GP_HD Vec3<T> operator-(Vec3<T> a) {
  return {-a.x, -a.y, -a.z};
}
template <typename T>
GP_HD Vec3<T> operator*(T s, Vec3<T> a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <typename T>
GP_HD T dot(Vec3<T> a, Vec3<T> b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <typename T>
GP_HD Vec3<T> cross(Vec3<T> a, Vec3<T> b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <typename T>
GP_HD T squared_norm(Vec3<T> a) {
  return dot(a, a);
}

// Rotation matrix by rows: r[i] is row i.
template <typename T>
struct Mat3 {
  Vec3<T> r[3];
  GP_HD Vec3<T> operator*(Vec3<T> v) const { return {dot(r[0], v), dot(r[1], v), dot(r[2], v)}; }
  GP_HD Vec3<T> column(int j) const { return {r[0][j], r[1][j], r[2][j]}; }
  // R^T v without forming the transpose.
  GP_HD Vec3<T> transpose_times(Vec3<T> v) const { return v.x * r[0] + v.y * r[1] + v.z * r[2]; }
};

template <typename T>
GP_HD Mat3<T> operator*(const Mat3<T>& a, const Mat3<T>& b) {
  Mat3<T> c;
  const Vec3<T> b0 = b.column(0), b1 = b.column(1), b2 = b.column(2);
  for (int i = 0; i < 3; ++i) c.r[i] = {dot(a.r[i], b0), dot(a.r[i], b1), dot(a.r[i], b2)};
  return c;
}

template <typename T>
GP_HD Mat3<T> transpose(const Mat3<T>& a) {
  return {{a.column(0), a.column(1), a.column(2)}};
}

template <typename T>
GP_HD Mat3<T> identity_rotation() {
  return {{{T(1), T(0), T(0)}, {T(0), T(1), T(0)}, {T(0), T(0), T(1)}}};
}

// A rigid transform X_AB: p_A = R * p_B + t.
template <typename T>
struct Transform {
  Mat3<T> R;
  Vec3<T> t;
  GP_HD Vec3<T> operator*(Vec3<T> p) const { return R * p + t; }
};

template <typename T>
GP_HD Transform<T> operator*(const Transform<T>& X_AB, const Transform<T>& X_BC) {
  return {X_AB.R * X_BC.R, X_AB.R * X_BC.t + X_AB.t};
}

template <typename T>
GP_HD Transform<T> inverse(const Transform<T>& X_AB) {
  const Mat3<T> Rt = transpose(X_AB.R);
  return {Rt, -(Rt * X_AB.t)};
}

template <typename T>
GP_HD Transform<T> identity_transform() {
  return {identity_rotation<T>(), {T(0), T(0), T(0)}};
}

// Rotation of angle `angle` about the unit axis u (Rodrigues).
template <typename T>
GP_HD Mat3<T> axis_angle(Vec3<T> u, T angle) {
  const T c = std::cos(angle), s = std::sin(angle), k = T(1) - c;
  return {{{c + u.x * u.x * k, u.x * u.y * k - u.z * s, u.x * u.z * k + u.y * s},
           {u.y * u.x * k + u.z * s, c + u.y * u.y * k, u.y * u.z * k - u.x * s},
           {u.z * u.x * k - u.y * s, u.z * u.y * k + u.x * s, c + u.z * u.z * k}}};
}

// Rotation of the quaternion (w, x, y, z), normalised first (rows may be given off
// unit length). Divided by its largest component before its length is taken, so that
// lengths whose squares would overflow or underflow (1e30, 1e-30 in float) normalise
// too. A zero quaternion gives NaN: callers reject it first.
template <typename T>
GP_HD Mat3<T> quaternion_rotation(T w, T x, T y, T z) {
  T m = std::fabs(w);
  m = std::fabs(x) > m ? std::fabs(x) : m;
  m = std::fabs(y) > m ? std::fabs(y) : m;
  m = std::fabs(z) > m ? std::fabs(z) : m;
  w /= m;
  x /= m;
  y /= m;
  z /= m;
  const T n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n;
  x /= n;
  y /= n;
  z /= n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

}  // namespace gplanner::geometry
