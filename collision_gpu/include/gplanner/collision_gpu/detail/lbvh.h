#pragma once
// The linear BVH of the sphere broad phase (gpu-lbvh), host and device: Morton codes of
// the centres, Karras' radix tree (2012) built a node at a time in parallel, and the query
// of one sphere against the tree for its later overlapping spheres. The tests build and
// query the same tree on the CPU, one node and one sphere at a time.
//
// Leaves are the spheres in Morton order (sorted positions 0 .. n-1); internal nodes are
// 0 .. n-2, node 0 the root. A child index c >= 0 is an internal node, c < 0 the leaf ~c.

#include <cstdint>

#include "gplanner/collision_gpu/geometry/host_device.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"

namespace gplanner::detail::lbvh {

// The deepest tree: 30 code bits, then up to 32 bits of the positions breaking ties.
inline constexpr int kMaxDepth = 64;

struct Node {
  int left, right;  // children (>= 0 internal, < 0 the leaf ~c)
  int first, last;  // the leaves (sorted positions) under the node
};

// An axis-aligned box: lo[3], hi[3].
struct Box {
  float lo[3], hi[3];
};

GP_HD bool boxes_overlap(const Box& a, const Box& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// The sphere's box, widened as the culling must be (geometry::cull_low/cull_high).
GP_HD Box sphere_box(float x, float y, float z, float r) {
  return {{geometry::cull_low(x, r), geometry::cull_low(y, r), geometry::cull_low(z, r)},
          {geometry::cull_high(x, r), geometry::cull_high(y, r), geometry::cull_high(z, r)}};
}

GP_HD Box merge(const Box& a, const Box& b) {
  Box m;
  for (int k = 0; k < 3; ++k) {
    m.lo[k] = a.lo[k] < b.lo[k] ? a.lo[k] : b.lo[k];
    m.hi[k] = a.hi[k] > b.hi[k] ? a.hi[k] : b.hi[k];
  }
  return m;
}

// 10 bits spread to every third of 30.
GP_HD std::uint32_t spread_bits(std::uint32_t v) {
  v = (v * 0x00010001u) & 0xFF0000FFu;
  v = (v * 0x00000101u) & 0x0F00F00Fu;
  v = (v * 0x00000011u) & 0xC30C30C3u;
  v = (v * 0x00000005u) & 0x49249249u;
  return v;
}

// The Morton code of a point of the box [lo, lo + size] (size 0 along an axis: 0 there).
GP_HD std::uint32_t morton_code(const float c[3], const float lo[3], const float size[3]) {
  std::uint32_t code = 0;
  for (int k = 0; k < 3; ++k) {
    float t = size[k] > 0 ? (c[k] - lo[k]) / size[k] * 1024.f : 0.f;
    t = t < 0.f ? 0.f : (t > 1023.f ? 1023.f : t);
    code |= spread_bits(static_cast<std::uint32_t>(t)) << (2 - k);
  }
  return code;
}

GP_HD int leading_zeros(std::uint32_t x) {
#if defined(__CUDA_ARCH__)
  return __clz(x);
#else
  return x == 0 ? 32 : __builtin_clz(x);
#endif
}

// The common prefix of the keys at positions i and j (the code, then the position
// breaking ties), -1 where j is outside [0, n).
GP_HD int common_prefix(const std::uint32_t* codes, int n, int i, int j) {
  if (j < 0 || j >= n) return -1;
  const std::uint32_t a = codes[i], b = codes[j];
  if (a != b) return leading_zeros(a ^ b);
  return 32 + leading_zeros(static_cast<std::uint32_t>(i) ^ static_cast<std::uint32_t>(j));
}

// Internal node i (0 .. n-2) of the radix tree over `codes` (sorted, n >= 2): the range
// of leaves it covers and where that range splits (Karras 2012, Figure 4).
GP_HD Node radix_node(const std::uint32_t* codes, int n, int i) {
  const int d = common_prefix(codes, n, i, i + 1) - common_prefix(codes, n, i, i - 1) >= 0 ? 1 : -1;
  const int min_prefix = common_prefix(codes, n, i, i - d);
  int length_max = 2;
  while (common_prefix(codes, n, i, i + length_max * d) > min_prefix) length_max *= 2;
  int length = 0;
  for (int t = length_max / 2; t >= 1; t /= 2)
    if (common_prefix(codes, n, i, i + (length + t) * d) > min_prefix) length += t;
  const int j = i + length * d;
  const int node_prefix = common_prefix(codes, n, i, j);
  int split = 0;
  int t = length;
  do {
    t = (t + 1) / 2;
    if (common_prefix(codes, n, i, i + (split + t) * d) > node_prefix) split += t;
  } while (t > 1);
  const int gamma = i + split * d + (d < 0 ? -1 : 0);
  Node node;
  node.first = i < j ? i : j;
  node.last = i < j ? j : i;
  node.left = node.first == gamma ? ~gamma : gamma;
  node.right = node.last == gamma + 1 ? ~(gamma + 1) : gamma + 1;
  return node;
}

// The spheres at sorted positions after k that overlap sphere k (the rule of
// geometry::spheres_overlap), each through emit(m): the subtrees whose leaves all come at
// or before k, and those whose box misses k's, are skipped.
template <typename Emit>
GP_HD void query_later(const Node* nodes, const Box* node_boxes, const Box* leaf_boxes,
                       const float* spheres /* shape [n, 4] sorted */, int k, Emit&& emit) {
  const Box box = leaf_boxes[k];
  const float* a = spheres + 4 * k;
  int stack[kMaxDepth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node node = nodes[stack[--top]];
    const int children[2] = {node.left, node.right};
    for (const int child : children) {
      if (child < 0) {
        const int m = ~child;
        const float* b = spheres + 4 * m;
        if (m > k && boxes_overlap(box, leaf_boxes[m]) &&
            geometry::spheres_overlap(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]))
          emit(m);
      } else if (nodes[child].last > k && boxes_overlap(box, node_boxes[child])) {
        stack[top++] = child;
      }
    }
  }
}

}  // namespace gplanner::detail::lbvh
