#include "gplanner/collision_gpu/solids.h"

#include "gplanner/collision_gpu/detail/containment.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "gplanner/collision_gpu/model_view.h"

namespace gplanner {
namespace {

struct Item {
  Eigen::Vector3d lo, hi;
  int component;  // index into FlatSolids::components
  double size;    // see ComponentNode::size
};

// A node's box around items [begin, end), rounded outward to float, and its size: the
// least of theirs (least_size) or the largest.
void fit_node(const std::vector<Item>& items, int begin, int end, bool least_size,
              ComponentNode* node) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  double size = items[begin].size;
  for (int i = begin; i < end; ++i) {
    lo = lo.cwiseMin(items[i].lo);
    hi = hi.cwiseMax(items[i].hi);
    size = least_size ? std::min(size, items[i].size) : std::max(size, items[i].size);
  }
  const Eigen::Vector3d center = (lo + hi) / 2, extent = (hi - lo) / 2;
  const double slack =
      8 * std::numeric_limits<float>::epsilon() * (center.norm() + extent.norm()) + 1e-30;
  for (int k = 0; k < 3; ++k) {
    node->center[k] = static_cast<float>(center[k]);
    node->extent[k] = static_cast<float>(extent[k] + slack);
  }
  // Rounded the conservative way: down for a least size, up for a largest.
  node->size =
      least_size ? static_cast<float>(size * (1 - 1e-6)) : static_cast<float>(size * (1 + 1e-6));
}

// A tree over the items (median split along the widest axis of their centres), its
// nodes appended to `tree`; returns the root and adds its depth to *deepest.
int build_tree(std::vector<Item> items, bool least_size, std::vector<ComponentNode>* tree,
               int* deepest) {
  if (items.empty()) return -1;
  struct Task {
    int node, begin, end, depth;
  };
  const int root = static_cast<int>(tree->size());
  tree->emplace_back();
  std::vector<Task> stack{{root, 0, static_cast<int>(items.size()), 1}};
  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    *deepest = std::max(*deepest, task.depth);
    fit_node(items, task.begin, task.end, least_size, &(*tree)[task.node]);
    if (task.end - task.begin == 1) {
      (*tree)[task.node].child = -items[task.begin].component - 1;
      continue;
    }
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector3d hi = -lo;
    for (int i = task.begin; i < task.end; ++i) {
      const Eigen::Vector3d c = (items[i].lo + items[i].hi) / 2;
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const int middle = (task.begin + task.end) / 2;
    std::nth_element(items.begin() + task.begin, items.begin() + middle, items.begin() + task.end,
                     [axis](const Item& a, const Item& b) {
                       return a.lo[axis] + a.hi[axis] < b.lo[axis] + b.hi[axis];
                     });
    const int left = static_cast<int>(tree->size());
    (*tree)[task.node].child = left;
    tree->emplace_back();
    tree->emplace_back();
    stack.push_back({left + 1, middle, task.end, task.depth + 1});
    stack.push_back({left, task.begin, middle, task.depth + 1});
  }
  return root;
}

}  // namespace

BodyComponent make_body_component(const double* vertices, int vertex_count, const int* triangles,
                                  int triangle_count, bool solid) {
  BodyComponent c;
  if (triangle_count <= 0) return c;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int t = 0; t < 3 * triangle_count; ++t) {
    const Eigen::Vector3d p(vertices[3 * triangles[t]], vertices[3 * triangles[t] + 1],
                            vertices[3 * triangles[t] + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  for (int k = 0; k < 3; ++k) {
    c.point[k] = static_cast<float>(vertices[3 * triangles[0] + k]);
    // Rounded outward to float.
    c.box_min[k] = std::nextafter(static_cast<float>(lo[k]), -std::numeric_limits<float>::max());
    c.box_max[k] = std::nextafter(static_cast<float>(hi[k]), std::numeric_limits<float>::max());
  }
  if (solid) c.solid = build_bvh(vertices, vertex_count, triangles, triangle_count);
  return c;
}

BodySolids FlatSolids::add_body(const std::vector<BodyComponent>& body) {
  std::vector<Item> points, solids;
  for (const BodyComponent& c : body) {
    Component flat{};
    for (int k = 0; k < 3; ++k) {
      flat.point[k] = c.point[k];
      // The box from its float corners, rounded outward again.
      const double lo = c.box_min[k], hi = c.box_max[k];
      flat.center[k] = static_cast<float>((lo + hi) / 2);
      flat.extent[k] =
          static_cast<float>((hi - lo) / 2 * (1 + 1e-6) + std::abs((lo + hi) / 2) * 1e-6 + 1e-30);
    }
    flat.solid_node_offset = -1;
    flat.solid_triangle_offset = 0;
    const int index = static_cast<int>(components.size());
    const Eigen::Vector3d p(c.point[0], c.point[1], c.point[2]);
    const Eigen::Vector3d side(double(c.box_max[0]) - c.box_min[0],
                               double(c.box_max[1]) - c.box_min[1],
                               double(c.box_max[2]) - c.box_min[2]);
    points.push_back({p, p, index, side.maxCoeff()});
    if (!c.solid.empty()) {
      flat.solid_node_offset = static_cast<std::int32_t>(nodes.size());
      flat.solid_triangle_offset = static_cast<std::int32_t>(triangles.size());
      nodes.insert(nodes.end(), c.solid.nodes.begin(), c.solid.nodes.end());
      triangles.insert(triangles.end(), c.solid.triangles.begin(), c.solid.triangles.end());
      deepest_bvh = std::max(deepest_bvh, bvh_depth(c.solid));
      solids.push_back({Eigen::Vector3d(c.box_min[0], c.box_min[1], c.box_min[2]),
                        Eigen::Vector3d(c.box_max[0], c.box_max[1], c.box_max[2]), index,
                        side.norm()});
    }
    components.push_back(flat);
  }
  BodySolids body_solids;
  body_solids.points = build_tree(std::move(points), true, &tree, &deepest_tree);
  body_solids.solids = build_tree(std::move(solids), false, &tree, &deepest_tree);
  return body_solids;
}

SolidsView FlatSolids::view() const {
  return {components.data(), tree.data(), nodes.data(), triangles.data()};
}

bool either_body_inside(const SolidsView& view, const BodySolids& a, const BodySolids& b,
                        const double R_AB[3][3], const double p_AB[3], double margin) {
  geometry::Transform<double> X_AB;
  for (int i = 0; i < 3; ++i) X_AB.R.r[i] = {R_AB[i][0], R_AB[i][1], R_AB[i][2]};
  X_AB.t = {p_AB[0], p_AB[1], p_AB[2]};
  return detail::either_inside(view, a, b, X_AB, margin);
}

}  // namespace gplanner
