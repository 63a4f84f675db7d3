#pragma once
// Are two triangles within a distance threshold of each other? The leaf test of the
// collision core. It reports true whenever the triangles intersect or come closer than
// `threshold`, and false only when they are farther apart: a distance test, not an
// intersection test, so that float rounding can only make it conservative by a margin
// the caller controls (see DESIGN.md, the tolerance band).

#include "gplanner/collision_gpu/geometry/vec3.h"

namespace gplanner::geometry {

// std::fmax and std::fmin as the standard defines them (a NaN gives the other argument;
// two NaNs, NaN), inline on the host: GCC calls libm for them unless NaNs are assumed
// away (-ffinite-math-only), and the leaf test's edge axes make up to ninety a triangle
// pair (perf, a piano plan on the cpu backend: 6 % of its samples in them and their
// stubs). The device keeps CUDA's (an instruction). A zero's sign may differ from libm's;
// the callers only compare and subtract them.
template <typename T>
GP_HD T max_number(T a, T b) {
#if defined(__CUDA_ARCH__)
  return fmax(a, b);
#else
  return a > b || b != b ? a : b;
#endif
}

template <typename T>
GP_HD T min_number(T a, T b) {
#if defined(__CUDA_ARCH__)
  return fmin(a, b);
#else
  return a < b || b != b ? a : b;
#endif
}

template <typename T>
GP_HD T clamp01(T v) {
  return v < T(0) ? T(0) : (v > T(1) ? T(1) : v);
}

// Squared distance between segments p1-q1 and p2-q2 (Ericson, Real-Time Collision
// Detection, 5.1.9), robust to zero-length segments.
template <typename T>
GP_HD T segment_segment_squared_distance(Vec3<T> p1, Vec3<T> q1, Vec3<T> p2, Vec3<T> q2) {
  const Vec3<T> d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const T a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  const T kTiny = T(1e-30);
  T s, t;
  if (a <= kTiny && e <= kTiny) return dot(r, r);
  if (a <= kTiny) {
    s = 0;
    t = clamp01(f / e);
  } else {
    const T c = dot(d1, r);
    if (e <= kTiny) {
      t = 0;
      s = clamp01(-c / a);
    } else {
      const T b = dot(d1, d2);
      const T denom = a * e - b * b;
      s = denom > kTiny * a * e ? clamp01((b * f - c * e) / denom) : T(0);
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = clamp01((b - c) / a);
      }
    }
  }
  const Vec3<T> gap = (p1 + s * d1) - (p2 + t * d2);
  return dot(gap, gap);
}

// Whether point x, known to lie near the plane of triangle abc with (unnormalised)
// normal n, projects inside the triangle (boundary included).
template <typename T>
GP_HD bool projects_inside(Vec3<T> x, Vec3<T> a, Vec3<T> b, Vec3<T> c, Vec3<T> n) {
  return dot(cross(b - a, x - a), n) >= 0 && dot(cross(c - b, x - b), n) >= 0 &&
         dot(cross(a - c, x - c), n) >= 0;
}

// A triangle's plane as far as rounding lets us trust it. A cross product of edges e1,
// e2 carries an error up to about 4 eps |e1| |e2|; where the normal is not much larger
// than that (slivers, collinear or coincident vertices), the plane is meaningless and
// the triangle is treated as its edges: every point of it lies within `thickness` of
// an edge.
template <typename T>
struct TrianglePlane {
  Vec3<T> n;      // unnormalised normal
  T length;       // |n|
  T error;        // bound on |n - exact normal|
  bool reliable;  // the plane may be used for face tests
  T thickness;    // for unreliable planes: how far the face strays from its edges
};

template <typename T>
GP_HD T machine_epsilon();
template <>
GP_HD float machine_epsilon<float>() {
  return 1.1920929e-7f;
}
template <>
GP_HD double machine_epsilon<double>() {
  return 2.220446049250313e-16;
}

template <typename T>
GP_HD TrianglePlane<T> triangle_plane(const Vec3<T> v[3]) {
  const Vec3<T> e1 = v[1] - v[0], e2 = v[2] - v[0], e3 = v[2] - v[1];
  TrianglePlane<T> plane;
  plane.n = cross(e1, e2);
  plane.length = std::sqrt(dot(plane.n, plane.n));
  const T l1 = std::sqrt(dot(e1, e1)), l2 = std::sqrt(dot(e2, e2)), l3 = std::sqrt(dot(e3, e3));
  plane.error = T(4) * machine_epsilon<T>() * l1 * l2;
  plane.reliable = plane.length > T(64) * plane.error;
  // Twice the area over the longest edge is the smallest height.
  const T longest = l1 > l2 ? (l1 > l3 ? l1 : l3) : (l2 > l3 ? l2 : l3);
  plane.thickness =
      plane.reliable || !(longest > 0) ? T(0) : (plane.length + plane.error) / longest;
  return plane;
}

// Whether all of triangle p lies farther than `threshold` on one side of q's plane,
// allowing for the rounding of the plane and of the distances.
template <typename T>
GP_HD bool beyond_plane(const Vec3<T> p[3], const Vec3<T> q0, const TrianglePlane<T>& plane,
                        T threshold) {
  if (!plane.reliable) return false;
  const T slope = plane.error + T(4) * machine_epsilon<T>() * plane.length;
  int above = 0, below = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3<T> r = p[k] - q0;
    const T limit = threshold * (plane.length + plane.error) + slope * std::sqrt(dot(r, r));
    const T d = dot(plane.n, r);
    above += d > limit;
    below += d < -limit;
  }
  return above == 3 || below == 3;
}

// Whether one of the nine axes across an edge of a and an edge of b (their cross
// products) parts the triangles by more than `threshold`: the separating-axis test's
// edge axes, in whatever precision T is, with its rounding bounded. Any axis L that
// parts the projections of the six vertices by a gap g proves the triangles at least
// g / |L| apart, so the computed axis serves as it is; what must be bounded is the
// rounding of the projections, taken relative to a[0] (each within
// 10 eps |L|_1 max|v - a[0]|), and |L| is replaced by its 1-norm, an upper bound that
// needs no square root and cannot underflow to zero while L does not. Degenerate axes
// (parallel edges) part nothing. The bound holds while the products stay normal
// numbers: in float, for edges and distances above about 1e-12 (their cubes above
// 1.2e-38), far below any robot's. Together with the two face planes these are the
// eleven axes of the triangle-triangle separating-axis test.
template <typename T>
GP_HD bool beyond_edge_axes(const Vec3<T> a[3], const Vec3<T> b[3], T threshold) {
  Vec3<T> ra[3], rb[3];
  T reach = 0;
  for (int k = 0; k < 3; ++k) {
    ra[k] = a[k] - a[0];
    rb[k] = b[k] - a[0];
    for (int c = 0; c < 3; ++c) {
      reach = max_number(reach, std::fabs(ra[k][c]));
      reach = max_number(reach, std::fabs(rb[k][c]));
    }
  }
  const T per_length = threshold * T(1.000001) + T(10) * machine_epsilon<T>() * reach;
  for (int i = 0; i < 3; ++i) {
    const Vec3<T> ea = ra[(i + 1) % 3] - ra[i];
    for (int j = 0; j < 3; ++j) {
      const Vec3<T> L = cross(ea, rb[(j + 1) % 3] - rb[j]);
      const T a1 = dot(L, ra[1]), a2 = dot(L, ra[2]);  // a[0] projects to 0
      const T b0 = dot(L, rb[0]), b1 = dot(L, rb[1]), b2 = dot(L, rb[2]);
      const T a_min = min_number(T(0), min_number(a1, a2));
      const T a_max = max_number(T(0), max_number(a1, a2));
      const T b_min = min_number(b0, min_number(b1, b2));
      const T b_max = max_number(b0, max_number(b1, b2));
      const T need = per_length * (std::fabs(L.x) + std::fabs(L.y) + std::fabs(L.z));
      if (b_min - a_max > need || a_min - b_max > need) return true;
    }
  }
  return false;
}

// Face tests of triangle p (its vertices and edges) against the face of triangle q:
// a vertex of p within `threshold` above or below q's face, or an edge of p crossing
// it. Edge-against-edge proximity is tested separately.
template <typename T>
GP_HD bool touches_face(const Vec3<T> p[3], const Vec3<T> q[3], const TrianglePlane<T>& plane,
                        T threshold) {
  if (!plane.reliable) return false;  // the edges stand for the face
  const T inv_n = T(1) / plane.length;
  const T slope = (plane.error + T(4) * machine_epsilon<T>() * plane.length) * inv_n;
  T s[3];
  for (int k = 0; k < 3; ++k) {
    const Vec3<T> r = p[k] - q[0];
    s[k] = dot(plane.n, r) * inv_n;  // signed distance of p's vertex to q's plane
    const T reach = threshold + slope * std::sqrt(dot(r, r));
    if (std::fabs(s[k]) <= reach && projects_inside(p[k], q[0], q[1], q[2], plane.n)) return true;
  }
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if ((s[k] > 0 && s[l] > 0) || (s[k] < 0 && s[l] < 0)) continue;  // no crossing
    const T denom = s[k] - s[l];
    if (denom == 0) continue;  // lies in the plane: the vertex and edge tests cover it
    const Vec3<T> x = p[k] + (s[k] / denom) * (p[l] - p[k]);
    if (projects_inside(x, q[0], q[1], q[2], plane.n)) return true;
  }
  return false;
}

// True when triangles a and b intersect or lie within `threshold` of each other (both
// given in one frame); false when they are farther apart, up to rounding of order
// eps times the coordinates. The distance between two triangles is reached
// edge-to-edge or vertex-to-face, or is zero where an edge crosses a face. The face
// tests come first: triangles that intersect (where an edge crosses a face) are found
// by them without the nine edge-to-edge distances.
template <typename T>
GP_HD bool triangles_within(const Vec3<T> a[3], const Vec3<T> b[3], T threshold) {
  const TrianglePlane<T> pa = triangle_plane(a), pb = triangle_plane(b);
  if (beyond_plane(b, a[0], pa, threshold) || beyond_plane(a, b[0], pb, threshold)) return false;
  if (touches_face(a, b, pb, threshold) || touches_face(b, a, pa, threshold)) return true;
  const T edge_threshold = threshold + pa.thickness + pb.thickness;
  const T threshold2 = edge_threshold * edge_threshold;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (segment_segment_squared_distance(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]) <=
          threshold2) {
        return true;
      }
    }
  }
  return false;
}

}  // namespace gplanner::geometry
