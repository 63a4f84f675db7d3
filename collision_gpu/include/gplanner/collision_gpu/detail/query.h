#pragma once
// One collision query on host or device, in the pieces every traversal shares: forward
// kinematics of a configuration, the checked bodies and their bounding-sphere broad
// phase, the box and leaf tests, the rule that splits a node pair, and the containment
// step that runs when no surfaces meet (query_contained). query_collides puts them
// together with a private stack per query (the `basic` traversal, and the CPU backend);
// the other traversals schedule the same pieces differently (src/traversals/).

#include "gplanner/collision_gpu/detail/containment.h"
#include "gplanner/collision_gpu/geometry/obb.h"
#include "gplanner/collision_gpu/geometry/triangle_distance.h"
#include "gplanner/collision_gpu/model_view.h"

namespace gplanner::detail {

constexpr int kMaxLinks = 128;
constexpr int kStackSize = 128;

using Xf = geometry::Transform<float>;
using V3f = geometry::Vec3<float>;

// Work done, for the comparison of traversals against the hardware's peak rates.
struct TraversalCounts {
  unsigned long long bv_tests = 0;
  unsigned long long triangle_tests = 0;
};

GP_HD Xf load_transform(const float* m) {
  return {{{{m[0], m[1], m[2]}, {m[3], m[4], m[5]}, {m[6], m[7], m[8]}}}, {m[9], m[10], m[11]}};
}

// Whether row q (shape: [m.width]) is a configuration at all: every entry finite and,
// for a floating base, a quaternion of non-zero length. Every traversal reports a row
// that is not as colliding (never free, whatever NaN would make of the tests).
GP_HD bool is_configuration(const CollisionModelView& m, const float* q) {
  bool finite = true;
  for (int k = 0; k < m.width; ++k) finite = finite && std::fabs(q[k]) <= 3.402823466e38f;
  if (finite && m.base == BaseKind::kFloating)
    return q[3] != 0.0f || q[4] != 0.0f || q[5] != 0.0f || q[6] != 0.0f;
  return finite;
}

// X_WR, the robot root in the world, for configuration q.
GP_HD Xf base_pose(const CollisionModelView& m, const float* q) {
  if (m.base == BaseKind::kFloating) {
    return {geometry::quaternion_rotation(q[3], q[4], q[5], q[6]), {q[0], q[1], q[2]}};
  }
  const Xf X_WB = load_transform(m.X_WB);
  if (m.base == BaseKind::kPlanar) {
    const Xf X_BR{geometry::axis_angle(V3f{0, 0, 1}, q[2]), {q[0], q[1], 0}};
    return X_WB * X_BR;
  }
  return X_WB;
}

// X_PL, link l (l >= 1) in its parent's frame, for configuration q.
GP_HD Xf joint_transform(const CollisionModelView& m, int l, const float* q) {
  const LinkKinematics& link = m.links[l];
  Xf X_PL = load_transform(link.X_PJ);
  if (link.motion != LinkMotion::kFixed) {
    const float value = link.multiplier * (link.source >= 0 ? q[link.source] : 0.0f) + link.offset;
    const V3f axis{link.axis[0], link.axis[1], link.axis[2]};
    if (link.motion == LinkMotion::kRevolute) {
      X_PL.R = X_PL.R * geometry::axis_angle(axis, value);
    } else {
      X_PL.t = X_PL.t + X_PL.R * (value * axis);
    }
  }
  return X_PL;
}

// X_WL of every link (shape: [m.link_count]).
GP_HD void link_poses(const CollisionModelView& m, const float* q, Xf* X_WL) {
  X_WL[0] = base_pose(m, q);
  for (int l = 1; l < m.link_count; ++l)
    X_WL[l] = X_WL[m.links[l].parent] * joint_transform(m, l, q);
}

GP_HD geometry::Vec3<double> widen(V3f p) { return {double(p.x), double(p.y), double(p.z)}; }

// Triangle ta of body A and tb of body B, B's vertices moved into A's frame by X_AB.
GP_HD void place_leaf_pair(const BvhTriangle& ta, const BvhTriangle& tb, const Xf& X_AB, V3f fa[3],
                           V3f fb[3]) {
  for (int k = 0; k < 3; ++k) {
    fa[k] = V3f{ta.v[k][0], ta.v[k][1], ta.v[k][2]};
    fb[k] = X_AB * V3f{tb.v[k][0], tb.v[k][1], tb.v[k][2]};
  }
}

// The leaf test's first stage, in float: true when a separating axis parts the
// triangles by more than the threshold, beyond its rounding. Most leaf pairs lie apart
// along one of the eleven axes (the two face normals, then the nine edge-against-edge
// axes); what is left is, nearly all, pairs that do touch. (Measured on the CPU backend,
// 20,000 configurations each: the face planes leave 70 to 78 % of the leaf pairs, the
// edge axes 2 to 15 % of those, of which over 99 % collide.)
GP_HD bool leaf_apart_in_float(const V3f fa[3], const V3f fb[3], float threshold) {
  return geometry::beyond_plane(fb, fa[0], geometry::triangle_plane(fa), threshold) ||
         geometry::beyond_plane(fa, fb[0], geometry::triangle_plane(fb), threshold) ||
         geometry::beyond_edge_axes(fa, fb, threshold);
}

// The leaf test's second stage, deciding the pairs the first leaves in double, so that
// only the float poses round.
GP_HD bool leaf_within_in_double(const V3f fa[3], const V3f fb[3], float threshold) {
  geometry::Vec3<double> a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = widen(fa[k]);
    b[k] = widen(fb[k]);
  }
  return geometry::triangles_within(a, b, double(threshold));
}

// The leaf test: whether triangle ta of body A and tb of body B (moved into A's frame
// by X_AB) come within the threshold.
GP_HD bool leaf_collides(const BvhTriangle& ta, const BvhTriangle& tb, const Xf& X_AB,
                         float threshold) {
  V3f fa[3], fb[3];
  place_leaf_pair(ta, tb, X_AB, fa, fb);
  return !leaf_apart_in_float(fa, fb, threshold) && leaf_within_in_double(fa, fb, threshold);
}

// Whether two nodes' boxes (B's placed in A's frame by X_AB) come within the margin:
// their bounding spheres first, which reject most far pairs for a few flops, then the
// separating-axis test.
GP_HD bool nodes_overlap(const BvhNode& na, const BvhNode& nb, const Xf& X_AB, float margin) {
  const V3f d = X_AB * V3f{nb.center[0], nb.center[1], nb.center[2]} -
                V3f{na.center[0], na.center[1], na.center[2]};
  const float reach = na.radius + nb.radius + margin;
  if (geometry::dot(d, d) > reach * reach) return false;
  return geometry::obbs_overlap(node_box(na), geometry::transformed(node_box(nb), X_AB), margin);
}

GP_HD float box_size(const BvhNode& n) {
  return n.extent[0] * n.extent[0] + n.extent[1] * n.extent[1] + n.extent[2] * n.extent[2];
}

// Which node of an overlapping inner pair to descend into: A's unless it is a leaf or
// B's box is the larger.
GP_HD bool splits_a(const BvhNode& na, const BvhNode& nb) {
  return !na.is_leaf() && (nb.is_leaf() || box_size(na) >= box_size(nb));
}

struct NodePair {
  int a, b;
};

// The two child pairs of an overlapping inner node pair (ia, ib), in the order of the
// split node's children; returns whether A's node was split. Every traversal splits by
// this rule and differs only in the order it visits the two pairs.
GP_HD bool split_node_pair(int ia, int ib, const BvhNode& na, const BvhNode& nb, NodePair* first,
                           NodePair* second) {
  if (splits_a(na, nb)) {
    *first = {na.child, ib};
    *second = {na.child + 1, ib};
    return true;
  }
  *first = {ia, nb.child};
  *second = {ia, nb.child + 1};
  return false;
}

// Whether point c (in node n's frame) lies on the side of n's split plane that n's
// second child holds.
GP_HD bool nearer_second_child(const BvhNode& n, V3f c) {
  return n.axes[0] * c.x + n.axes[3] * c.y + n.axes[6] * c.z >= n.split;
}

// split_node_pair in depth-first order: the child on the same side of the split node's
// split plane as the other node's centre comes first, being the likelier to hold a
// collision, so that a query stops sooner. The children themselves are not loaded: on
// the GPU that load was a second dependent memory access in every step (measured:
// benchmarks/history/tuning_notes.md, "split_pair's order"). X_BA is the inverse of X_AB,
// computed once per body pair by the caller.
GP_HD void split_pair(const Xf& X_AB, const Xf& X_BA, int ia, int ib, const BvhNode& na,
                      const BvhNode& nb, NodePair* first, NodePair* second) {
  const bool swap =
      split_node_pair(ia, ib, na, nb, first, second)
          ? nearer_second_child(na, X_AB * V3f{nb.center[0], nb.center[1], nb.center[2]})
          : nearer_second_child(nb, X_BA * V3f{na.center[0], na.center[1], na.center[2]});
  if (swap) {
    const NodePair later = *first;
    *first = *second;
    *second = later;
  }
}

// The leaf threshold and BV margin one checked body of a query is tested with.
struct BodyTolerance {
  float threshold, margin;
};

// The model's, raised by the body's clearance when the query has clearances (its row
// `clearances`, or null; CollisionModelView::clearances). A clearance that is not a
// number makes every test of the body overlap: colliding, never free.
GP_HD BodyTolerance body_tolerance(const CollisionModelView& m, int body, const float* clearances) {
  if (!clearances) return {m.threshold, m.margin};
  float extra;
  if (body < m.link_count) {
    extra = clearances[body];
  } else {
    const int p = body - m.link_count;
    extra = clearances[m.pair_a[p]] + clearances[m.pair_b[p]] - 2 * clearances[m.pair_ancestor[p]];
  }
  if (extra != extra) extra = 3.0e38f;
  const float threshold = m.threshold + (extra > 0 ? extra : 0.0f);
  return {threshold, 2 * threshold};
}

// Whether bodies A and B (B placed in A's frame by X_AB) come within the threshold:
// a depth-first walk of their BVTT with a private stack, in split_pair's order.
GP_HD bool bodies_collide(const CollisionModelView& m, BodyRange a, BodyRange b, const Xf& X_AB,
                          BodyTolerance tolerance, TraversalCounts* counts) {
  const Xf X_BA = geometry::inverse(X_AB);
  int stack_a[kStackSize], stack_b[kStackSize];
  int top = 0;
  stack_a[0] = 0;
  stack_b[0] = 0;
  top = 1;
  while (top > 0) {
    --top;
    const int ia = stack_a[top], ib = stack_b[top];
    const BvhNode& na = m.nodes[a.node_offset + ia];
    const BvhNode& nb = m.nodes[b.node_offset + ib];
    if (counts) ++counts->bv_tests;
    if (!nodes_overlap(na, nb, X_AB, tolerance.margin)) continue;
    if (na.is_leaf() && nb.is_leaf()) {
      if (counts) ++counts->triangle_tests;
      if (leaf_collides(m.triangles[a.triangle_offset + na.triangle()],
                        m.triangles[b.triangle_offset + nb.triangle()], X_AB,
                        tolerance.threshold)) {
        return true;
      }
      continue;
    }
    NodePair first, second;
    split_pair(X_AB, X_BA, ia, ib, na, nb, &first, &second);
    stack_a[top] = second.a;
    stack_b[top] = second.b;
    ++top;
    stack_a[top] = first.a;
    stack_b[top] = first.b;
    ++top;
  }
  return false;
}

GP_HD V3f sphere_center_W(const CollisionModelView& m, int link, const Xf& X_WL) {
  const LinkSphere& s = m.link_spheres[link];
  return X_WL * V3f{s.center[0], s.center[1], s.center[2]};
}

// Broad phase of link l against the environment: its bounding sphere (centre c_W in the
// world) against the environment's root box, within `margin`.
GP_HD bool sphere_may_touch_environment(const CollisionModelView& m, int l, V3f c_W, float margin) {
  if (m.environment.node_offset < 0 || m.link_bodies[l].node_offset < 0) return false;
  return geometry::sphere_overlaps_obb(c_W, m.link_spheres[l].radius,
                                       node_box(m.nodes[m.environment.node_offset]), margin);
}

// Broad phase of a checked link pair: bounding sphere against bounding sphere (centres
// ca_W and cb_W in the world), within `margin`.
GP_HD bool spheres_may_touch(const CollisionModelView& m, int p, V3f ca_W, V3f cb_W, float margin) {
  const V3f d = ca_W - cb_W;
  const float reach =
      m.link_spheres[m.pair_a[p]].radius + m.link_spheres[m.pair_b[p]].radius + margin;
  return geometry::dot(d, d) <= reach * reach;
}

// The checked bodies of a query, numbered 0 .. body_count(m) - 1 and visited in this
// order by every traversal: body b < m.link_count is link b against the environment,
// body m.link_count + p the checked link pair p.
GP_HD int body_count(const CollisionModelView& m) { return m.link_count + m.pair_count; }

// A checked body's two bodies' entries of one kind, A and B: the environment's and link
// b's for body b < m.link_count, else the pair's two links'.
template <typename T>
struct BodyPair {
  T a, b;
};

template <typename T>
GP_HD BodyPair<T> body_pair(const CollisionModelView& m, int body, const T& environment,
                            const T* links) {
  if (body < m.link_count) return {environment, links[body]};
  const int p = body - m.link_count;
  return {links[m.pair_a[p]], links[m.pair_b[p]]};
}

using BodyRanges = BodyPair<BodyRange>;

GP_HD BodyRanges body_ranges(const CollisionModelView& m, int body) {
  return body_pair(m, body, m.environment, m.link_bodies);
}

// X_AB, body B in body A's frame; X_WL(l) gives link l's pose in the world.
template <typename LinkPose>
GP_HD Xf body_transform(const CollisionModelView& m, int body, LinkPose X_WL) {
  if (body < m.link_count) return X_WL(body);
  const int p = body - m.link_count;
  return geometry::inverse(X_WL(m.pair_a[p])) * X_WL(m.pair_b[p]);
}

// The broad phase of a body, within `margin` (its BodyTolerance's); c_W(l) gives the
// centre of link l's bounding sphere in the world.
template <typename SphereCentre>
GP_HD bool body_may_touch(const CollisionModelView& m, int body, SphereCentre c_W, float margin) {
  if (body < m.link_count) return sphere_may_touch_environment(m, body, c_W(body), margin);
  const int p = body - m.link_count;
  return spheres_may_touch(m, p, c_W(m.pair_a[p]), c_W(m.pair_b[p]), margin);
}

// The solid components of a checked body's two bodies, A and B as body_ranges names them.
using BodySolidsPair = BodyPair<BodySolids>;

GP_HD BodySolidsPair body_solids(const CollisionModelView& m, int body) {
  return body_pair(m, body, m.environment_solids, m.link_solids);
}

// The containment step of one checked body (numbered as body_count's), once its two
// bodies' surfaces are known to be apart: whether a component of either lies inside a
// solid component of the other (containment.h), within `margin` (its BodyTolerance's).
// X_WL(l) gives link l's pose.
template <typename LinkPose>
GP_HD bool body_contained(const CollisionModelView& m, int body, LinkPose X_WL, float margin) {
  const BodySolidsPair s = body_solids(m, body);
  return either_inside(m.solids, s.a, s.b, body_transform(m, body, X_WL), margin);
}

// The containment step of a query whose surface tests found no collision: whether a
// link lies inside a solid obstacle or an obstacle inside a solid link, or a link of a
// checked pair inside the other. Only bodies past the broad phase can (a body inside
// another lies within its bounding volumes); nothing runs when the model has no solid
// on either side of any checked body (m.containment). X_WL: the query's link poses;
// clearances: its row, or null.
GP_HD bool query_contained(const CollisionModelView& m, const Xf* X_WL, const float* clearances) {
  if (!m.containment) return false;
  const auto pose = [&](int l) { return X_WL[l]; };
  const auto centre = [&](int l) { return sphere_center_W(m, l, X_WL[l]); };
  for (int body = 0; body < body_count(m); ++body) {
    const float margin = body_tolerance(m, body, clearances).margin;
    if (body_may_touch(m, body, centre, margin) && body_contained(m, body, pose, margin))
      return true;
  }
  return false;
}

// The whole query: true when configuration q (shape: [m.width]) collides with the
// environment or with itself, or is no configuration (is_configuration). X_WL: scratch for
// m.link_count poses; clearances: the query's row, or null.
GP_HD bool query_collides(const CollisionModelView& m, const float* q, const float* clearances,
                          Xf* X_WL, TraversalCounts* counts) {
  if (!is_configuration(m, q)) return true;
  link_poses(m, q, X_WL);
  const auto pose = [&](int l) { return X_WL[l]; };
  const auto centre = [&](int l) { return sphere_center_W(m, l, X_WL[l]); };
  for (int body = 0; body < body_count(m); ++body) {
    const BodyTolerance tolerance = body_tolerance(m, body, clearances);
    if (!body_may_touch(m, body, centre, tolerance.margin)) continue;
    const BodyRanges r = body_ranges(m, body);
    if (bodies_collide(m, r.a, r.b, body_transform(m, body, pose), tolerance, counts)) return true;
  }
  return query_contained(m, X_WL, clearances);
}

}  // namespace gplanner::detail
