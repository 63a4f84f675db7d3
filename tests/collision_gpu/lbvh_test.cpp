// The linear BVH's core (detail/lbvh.h), built and queried on the CPU one node and one
// sphere at a time as the GPU does it in parallel: a valid radix tree (every leaf once,
// ranges nested), and exactly the all-pairs pair set.

#include "gplanner/collision_gpu/detail/lbvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "collision_gpu/sphere_scenes.h"

namespace gplanner {
namespace {

using detail::lbvh::Box;
using detail::lbvh::Node;

struct HostTree {
  std::vector<std::uint32_t> codes;  // shape [n], sorted
  std::vector<std::uint32_t> ids;    // shape [n]: sorted position -> sphere
  std::vector<float> spheres;        // shape [n, 4], sorted
  std::vector<Node> nodes;           // shape [n - 1]
  std::vector<Box> node_boxes;       // shape [n - 1]
  std::vector<Box> leaf_boxes;       // shape [n]
};

Box refit(HostTree& t, int node) {
  const Node& x = t.nodes[node];
  const auto box = [&](int c) { return c < 0 ? t.leaf_boxes[~c] : refit(t, c); };
  return t.node_boxes[node] = detail::lbvh::merge(box(x.left), box(x.right));
}

HostTree build(const testing::SphereScene& s) {
  const int n = int(s.size());
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f}, size[3];
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], s.centers[3 * i + k]);
      hi[k] = std::max(hi[k], s.centers[3 * i + k]);
    }
  for (int k = 0; k < 3; ++k) size[k] = hi[k] - lo[k];
  std::vector<std::uint32_t> codes(n);
  for (int i = 0; i < n; ++i) codes[i] = detail::lbvh::morton_code(&s.centers[3 * i], lo, size);
  HostTree t;
  t.ids.resize(n);
  std::iota(t.ids.begin(), t.ids.end(), 0u);
  std::stable_sort(t.ids.begin(), t.ids.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return codes[a] < codes[b]; });
  for (int k = 0; k < n; ++k) {
    const std::uint32_t i = t.ids[k];
    t.codes.push_back(codes[i]);
    t.spheres.insert(t.spheres.end(),
                     {s.centers[3 * i], s.centers[3 * i + 1], s.centers[3 * i + 2], s.radii[i]});
    t.leaf_boxes.push_back(detail::lbvh::sphere_box(s.centers[3 * i], s.centers[3 * i + 1],
                                                    s.centers[3 * i + 2], s.radii[i]));
  }
  for (int i = 0; i + 1 < n; ++i) t.nodes.push_back(detail::lbvh::radix_node(t.codes.data(), n, i));
  t.node_boxes.resize(std::max(n - 1, 0));
  if (n >= 2) refit(t, 0);
  return t;
}

// Every leaf under the root once, each child's range inside its parent's.
void expect_valid_tree(const HostTree& t) {
  const int n = int(t.codes.size());
  std::vector<int> seen(n, 0);
  std::vector<int> stack = {0};
  int depth = 0;
  std::vector<int> depths = {1};
  while (!stack.empty()) {
    const int node = stack.back();
    const int d = depths.back();
    stack.pop_back();
    depths.pop_back();
    depth = std::max(depth, d);
    const Node& x = t.nodes[node];
    for (const int c : {x.left, x.right}) {
      if (c < 0) {
        ASSERT_GE(~c, x.first);
        ASSERT_LE(~c, x.last);
        ++seen[~c];
      } else {
        ASSERT_GE(t.nodes[c].first, x.first);
        ASSERT_LE(t.nodes[c].last, x.last);
        stack.push_back(c);
        depths.push_back(d + 1);
      }
    }
  }
  for (int k = 0; k < n; ++k) ASSERT_EQ(seen[k], 1) << "leaf " << k;
  EXPECT_LT(depth, detail::lbvh::kMaxDepth);
}

std::vector<SpherePair> lbvh_pairs(const testing::SphereScene& s) {
  std::vector<SpherePair> pairs;
  if (s.size() < 2) return pairs;
  const HostTree t = build(s);
  expect_valid_tree(t);
  for (int k = 0; k < int(s.size()); ++k) {
    detail::lbvh::query_later(t.nodes.data(), t.node_boxes.data(), t.leaf_boxes.data(),
                              t.spheres.data(), k, [&](int m) {
                                const std::uint32_t a = t.ids[k], b = t.ids[m];
                                pairs.push_back({std::min(a, b), std::max(a, b)});
                              });
  }
  sort_pairs(&pairs);
  return pairs;
}

void expect_all_pairs(const testing::SphereScene& s) {
  std::vector<SpherePair> expected;
  all_pairs_cpu(s.arrays(), &expected);
  EXPECT_EQ(lbvh_pairs(s), expected);
}

TEST(BroadPhaseLbvh, RadixTreeAndPairsMatchAllPairs) {
  testing::SphereScene two;
  two.add(0, 0, 0, 1);
  two.add(2, 0, 0, 1);
  expect_all_pairs(two);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    expect_all_pairs(testing::uniform_spheres(1200, seed, 20.f, 0.2f, 0.6f));
    expect_all_pairs(testing::clustered_spheres(1000, seed + 3, 4));
    expect_all_pairs(testing::mixed_radii_spheres(1000, seed + 6, 50.f));
  }
  expect_all_pairs(testing::uniform_spheres(400, 9, 1.f, 2.f, 3.f));  // all overlap
  for (const float origin : {0.f, 65536.f})
    expect_all_pairs(testing::lattice_spheres(8, origin, 0.5f));
  testing::SphereScene points;  // every code equal: the positions break the ties
  for (int i = 0; i < 500; ++i) points.add(1.f, 2.f, 3.f, 0.f);
  expect_all_pairs(points);
}

}  // namespace
}  // namespace gplanner
