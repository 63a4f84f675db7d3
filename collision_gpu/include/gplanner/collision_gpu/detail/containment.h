#pragma once
// The containment step's geometry, on host or device (docs/design.md, "Solids"): whether
// some component of body A lies inside a solid component of body B, asked only once
// their surfaces are known to be apart, so that one point per component decides. A's
// tree over its component points meets B's tree over its solid components' boxes; a
// point inside such a box is tested by rays through that component's own BVH, in double.
// query.h calls it per body pair of a query (query_contained); the fcl backend calls it
// with its double poses, so that the ground truth applies the same rule.

#include "gplanner/collision_gpu/geometry/vec3.h"
#include "gplanner/collision_gpu/solids.h"

namespace gplanner::detail {

constexpr int kComponentStackSize = 64;  // node pairs: twice the deepest component tree
constexpr int kRayStackSize = 128;       // nodes: the deepest solid component BVH

using V3d = geometry::Vec3<double>;

template <typename T>
GP_HD geometry::Vec3<T> component_point(const Component& c) {
  return {T(c.point[0]), T(c.point[1]), T(c.point[2])};
}

// The three directions of the point-in-solid rays: unit vectors whose components have
// irrational ratios ((1, sqrt 2, sqrt 3), (-sqrt 5, 1, pi - 3), (e - 2, -sqrt 7 / 2, 1),
// normalised), so that a ray meets an edge or vertex of a mesh modelled on a grid only
// by accident; two of three must agree.
GP_HD V3d containment_ray(int k) {
  if (k == 0) return {0.40824829046386307, 0.57735026918962584, 0.70710678118654757};
  if (k == 1) return {-0.91134960114169505, 0.40756793188403001, 0.057708624993563856};
  return {0.39745825753453246, -0.732007733107643, 0.5533458341654186};
}

// Whether the ray p + t d (t >= 0) meets node n's box, in double, the box grown by a
// little more than float's rounding of it.
GP_HD bool ray_meets_box(const BvhNode& n, V3d p, V3d d) {
  const V3d c{n.center[0], n.center[1], n.center[2]};
  const V3d pc = p - c;
  const double slack = 1e-5 * (n.radius + std::sqrt(geometry::dot(c, c)));
  double near = 0, far = 1e300;
  for (int i = 0; i < 3; ++i) {
    const V3d axis{n.axes[i], n.axes[3 + i], n.axes[6 + i]};
    const double o = geometry::dot(axis, pc), v = geometry::dot(axis, d);
    const double e = double(n.extent[i]) + slack;
    if (std::fabs(v) < 1e-300) {
      if (std::fabs(o) > e) return false;
      continue;
    }
    double t0 = (-e - o) / v, t1 = (e - o) / v;
    if (t0 > t1) {
      const double swap = t0;
      t0 = t1;
      t1 = swap;
    }
    near = t0 > near ? t0 : near;
    far = t1 < far ? t1 : far;
    if (near > far) return false;
  }
  return true;
}

// Whether p lies in node n's box, in double, the box grown as ray_meets_box grows it. A
// point outside a solid component's root box is outside the component: its rays are not
// cast (MotionBenchMaker's box 0001, 256 Panda configurations on one core: link 6's
// containment work 139 to 25 us, its points in obstacles' axis-aligned boxes but seldom
// in their oriented ones).
GP_HD bool point_in_node_box(const BvhNode& n, V3d p) {
  const V3d c{n.center[0], n.center[1], n.center[2]};
  const V3d pc = p - c;
  const double slack = 1e-5 * (n.radius + std::sqrt(geometry::dot(c, c)));
  for (int i = 0; i < 3; ++i) {
    const V3d axis{n.axes[i], n.axes[3 + i], n.axes[6 + i]};
    if (std::fabs(geometry::dot(axis, pc)) > double(n.extent[i]) + slack) return false;
  }
  return true;
}

// How the ray p + t d (t > 0) crosses triangle tri, in double (Moller-Trumbore): +1
// through its front (its normal, counter-clockwise, along d), -1 through its back, 0
// when it misses.
GP_HD int ray_crossing(const BvhTriangle& tri, V3d p, V3d d) {
  const V3d a{tri.v[0][0], tri.v[0][1], tri.v[0][2]};
  const V3d e1 = V3d{tri.v[1][0], tri.v[1][1], tri.v[1][2]} - a;
  const V3d e2 = V3d{tri.v[2][0], tri.v[2][1], tri.v[2][2]} - a;
  const V3d h = geometry::cross(d, e2);
  const double det = geometry::dot(e1, h);  // -(d . (e1 x e2))
  if (det == 0) return 0;
  const double inverse = 1 / det;
  const V3d s = p - a;
  const double u = geometry::dot(s, h) * inverse;
  if (u < 0 || u > 1) return 0;
  const V3d q = geometry::cross(s, e1);
  const double v = geometry::dot(d, q) * inverse;
  if (v < 0 || u + v > 1) return 0;
  if (geometry::dot(e2, q) * inverse <= 0) return 0;
  return det < 0 ? 1 : -1;
}

// The winding number of solid component c about p along the ray p + t d: the crossings'
// signed sum over c's own triangles (+1 inside a closed mesh whose triangles face
// outward, -1 inside one facing inward, 0 outside), unless the ray grazes an edge.
GP_HD int ray_winding(const SolidsView& s, const Component& c, V3d p, V3d d) {
  int stack[kRayStackSize];
  int top = 0;
  stack[top++] = 0;
  int winding = 0;
  while (top > 0) {
    const BvhNode& n = s.nodes[c.solid_node_offset + stack[--top]];
    if (!ray_meets_box(n, p, d)) continue;
    if (n.is_leaf()) {
      winding += ray_crossing(s.triangles[c.solid_triangle_offset + n.triangle()], p, d);
    } else {
      stack[top++] = n.child;
      stack[top++] = n.child + 1;
    }
  }
  return winding;
}

// Whether p (in c's body frame) lies inside solid component c: a nonzero winding number
// along two of the three rays.
GP_HD bool point_in_solid(const SolidsView& s, const Component& c, V3d p) {
  const bool first = ray_winding(s, c, p, containment_ray(0)) != 0;
  const bool second = ray_winding(s, c, p, containment_ray(1)) != 0;
  if (first == second) return first;
  return ray_winding(s, c, p, containment_ray(2)) != 0;
}

// Whether some component of body A lies inside a solid component of body B, given that
// their surfaces do not come within the threshold; X_BA places A in B's frame, margin
// grows every box test. A's point tree against B's solid tree, depth first (a point
// against a box directly, in B's frame); a point in a solid component's axis-aligned
// box and in its BVH's root box (point_in_node_box) is handed to point_test(c, p) (p in
// B's frame), which says whether it lies inside c (true ends the walk):
// components_inside below tests it at once, the GPU's balanced traversal queues it for a
// thread of its own per ray.
template <typename T, typename PointTest>
GP_HD bool components_inside_by(const SolidsView& s, BodySolids a, BodySolids b,
                                const geometry::Transform<T>& X_BA, T margin,
                                PointTest&& point_test) {
  if (a.points < 0 || b.solids < 0) return false;
  geometry::Mat3<T> abs_R;
  for (int i = 0; i < 3; ++i)
    abs_R.r[i] = {std::fabs(X_BA.R.r[i].x), std::fabs(X_BA.R.r[i].y), std::fabs(X_BA.R.r[i].z)};
  int stack_a[kComponentStackSize], stack_b[kComponentStackSize];
  int top = 0;
  stack_a[top] = a.points;
  stack_b[top] = b.solids;
  ++top;
  while (top > 0) {
    --top;
    const int ia = stack_a[top], ib = stack_b[top];
    const ComponentNode& na = s.tree[ia];
    const ComponentNode& nb = s.tree[ib];
    if (na.size > nb.size + margin) continue;  // all below A too large to fit in B
    const geometry::Vec3<T> c_b{T(nb.center[0]), T(nb.center[1]), T(nb.center[2])};
    const geometry::Vec3<T> e_b{T(nb.extent[0]), T(nb.extent[1]), T(nb.extent[2])};
    if (na.is_leaf()) {
      // A's component point against B's axis-aligned box, in B's frame.
      const geometry::Vec3<T> p_B = X_BA * component_point<T>(s.components[na.component()]);
      const geometry::Vec3<T> d = p_B - c_b;
      if (std::fabs(d.x) > e_b.x + margin || std::fabs(d.y) > e_b.y + margin ||
          std::fabs(d.z) > e_b.z + margin)
        continue;
      if (nb.is_leaf()) {
        const V3d p{double(p_B.x), double(p_B.y), double(p_B.z)};
        const Component& c = s.components[nb.component()];
        if (point_in_node_box(s.nodes[c.solid_node_offset], p) && point_test(nb.component(), p))
          return true;
        continue;
      }
      stack_a[top] = ia;
      stack_b[top] = nb.child;
      ++top;
      stack_a[top] = ia;
      stack_b[top] = nb.child + 1;
      ++top;
      continue;
    }
    // A's box as the axis-aligned box around it in B's frame: looser than the
    // separating-axis test, a fraction of its cost, and the points are tested exactly.
    const geometry::Vec3<T> e_a{T(na.extent[0]), T(na.extent[1]), T(na.extent[2])};
    const geometry::Vec3<T> c_a =
        X_BA * geometry::Vec3<T>{T(na.center[0]), T(na.center[1]), T(na.center[2])};
    const geometry::Vec3<T> reach_a = abs_R * e_a;
    const geometry::Vec3<T> d = c_a - c_b;
    if (std::fabs(d.x) > reach_a.x + e_b.x + margin ||
        std::fabs(d.y) > reach_a.y + e_b.y + margin || std::fabs(d.z) > reach_a.z + e_b.z + margin)
      continue;
    const bool split_a = nb.is_leaf() || geometry::dot(e_a, e_a) >= geometry::dot(e_b, e_b);
    stack_a[top] = split_a ? na.child : ia;
    stack_b[top] = split_a ? ib : nb.child;
    ++top;
    stack_a[top] = split_a ? na.child + 1 : ia;
    stack_b[top] = split_a ? ib : nb.child + 1;
    ++top;
  }
  return false;
}

// The same, each point tested by point_in_solid as it is found.
template <typename T>
GP_HD bool components_inside(const SolidsView& s, BodySolids a, BodySolids b,
                             const geometry::Transform<T>& X_BA, T margin) {
  return components_inside_by(s, a, b, X_BA, margin, [&](int component, V3d p) {
    return point_in_solid(s, s.components[component], p);
  });
}

// Whether a component of either body lies inside a solid component of the other (B
// placed in A's frame by X_AB).
template <typename T>
GP_HD bool either_inside(const SolidsView& s, BodySolids a, BodySolids b,
                         const geometry::Transform<T>& X_AB, T margin) {
  return components_inside(s, b, a, X_AB, margin) ||
         components_inside(s, a, b, geometry::inverse(X_AB), margin);
}

}  // namespace gplanner::detail
