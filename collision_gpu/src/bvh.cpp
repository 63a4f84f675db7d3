#include "gplanner/collision_gpu/bvh.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace gplanner {
namespace {

struct BuildTask {
  int node;
  int begin, end;  // range of the triangle order
};

// Principal axes of the vertices of triangles order[begin, end), as a right-handed
// rotation whose first column is the axis of largest spread.
Eigen::Matrix3d principal_axes(const std::vector<Eigen::Vector3d>& corners,
                               const std::vector<int>& order, int begin, int end) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = begin; i < end; ++i) {
    for (int k = 0; k < 3; ++k) mean += corners[3 * order[i] + k];
  }
  mean /= 3.0 * (end - begin);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int i = begin; i < end; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = corners[3 * order[i] + k] - mean;
      covariance += d * d.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d axes;
  // Eigenvalues ascend: take them in reverse so that column 0 is the widest axis.
  for (int c = 0; c < 3; ++c) axes.col(c) = solver.eigenvectors().col(2 - c).normalized();
  if (!axes.allFinite()) axes.setIdentity();
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  axes.col(1) = axes.col(2).cross(axes.col(0));
  return axes;
}

// Fits the box with the given axes around the triangles and rounds it outward to float.
void fit_node(const std::vector<Eigen::Vector3d>& corners, const std::vector<int>& order, int begin,
              int end, const Eigen::Matrix3d& axes, BvhNode* node) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (int i = begin; i < end; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = axes.transpose() * corners[3 * order[i] + k];
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  const Eigen::Vector3d center = axes * ((lo + hi) / 2);
  const Eigen::Vector3d extent = (hi - lo) / 2;
  // float rounding of centre, axes and extents: grow the box by a few ulps of its size
  // and position so that it still contains every vertex.
  const double slack =
      8 * std::numeric_limits<float>::epsilon() * (center.norm() + extent.norm()) + 1e-30;
  for (int k = 0; k < 3; ++k) {
    node->center[k] = static_cast<float>(center[k]);
    node->extent[k] = static_cast<float>(extent[k] + slack);
    for (int c = 0; c < 3; ++c) node->axes[3 * k + c] = static_cast<float>(axes(k, c));
  }
  node->radius = static_cast<float>((extent.array() + slack).matrix().norm() * (1 + 1e-6));
}

}  // namespace

Bvh build_bvh(const double* vertices, int vertex_count, const int* triangles, int triangle_count) {
  Bvh bvh;
  if (triangle_count <= 0) return bvh;
  std::vector<Eigen::Vector3d> corners(3 * static_cast<std::size_t>(triangle_count));
  std::vector<Eigen::Vector3d> centroids(triangle_count);
  for (int t = 0; t < triangle_count; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[3 * t + k];
      corners[3 * t + k] =
          Eigen::Vector3d(vertices[3 * v], vertices[3 * v + 1], vertices[3 * v + 2]);
    }
    centroids[t] = (corners[3 * t] + corners[3 * t + 1] + corners[3 * t + 2]) / 3;
  }
  (void)vertex_count;
  std::vector<int> order(triangle_count);
  std::iota(order.begin(), order.end(), 0);

  bvh.nodes.reserve(2 * static_cast<std::size_t>(triangle_count) - 1);
  bvh.nodes.emplace_back();
  std::vector<BuildTask> stack{{0, 0, triangle_count}};
  std::vector<int> leaf_triangle;  // triangle of each leaf, in leaf order
  leaf_triangle.reserve(triangle_count);
  while (!stack.empty()) {
    const BuildTask task = stack.back();
    stack.pop_back();
    const Eigen::Matrix3d axes = principal_axes(corners, order, task.begin, task.end);
    fit_node(corners, order, task.begin, task.end, axes, &bvh.nodes[task.node]);
    if (task.end - task.begin == 1) {
      bvh.nodes[task.node].child = -static_cast<int>(leaf_triangle.size()) - 1;
      leaf_triangle.push_back(order[task.begin]);
      continue;
    }
    // Split at the mean centroid along the widest axis (as FCL does), unless that
    // leaves one side with under a quarter of the triangles: then at the median.
    const Eigen::Vector3d axis = axes.col(0);
    double mean = 0;
    for (int i = task.begin; i < task.end; ++i) mean += axis.dot(centroids[order[i]]);
    mean /= task.end - task.begin;
    int middle =
        static_cast<int>(std::partition(order.begin() + task.begin, order.begin() + task.end,
                                        [&](int t) { return axis.dot(centroids[t]) < mean; }) -
                         order.begin());
    const int count = task.end - task.begin;
    double split = mean;
    if (4 * (middle - task.begin) < count || 4 * (task.end - middle) < count) {
      middle = (task.begin + task.end) / 2;
      std::nth_element(
          order.begin() + task.begin, order.begin() + middle, order.begin() + task.end,
          [&](int a, int b) { return axis.dot(centroids[a]) < axis.dot(centroids[b]); });
      split = axis.dot(centroids[order[middle]]);
    }
    bvh.nodes[task.node].split = static_cast<float>(split);
    const int left = static_cast<int>(bvh.nodes.size());
    bvh.nodes[task.node].child = left;
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    stack.push_back({left + 1, middle, task.end});
    stack.push_back({left, task.begin, middle});
  }
  bvh.triangles.resize(leaf_triangle.size());
  for (std::size_t i = 0; i < leaf_triangle.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = corners[3 * leaf_triangle[i] + k];
      bvh.triangles[i].v[k][0] = static_cast<float>(p.x());
      bvh.triangles[i].v[k][1] = static_cast<float>(p.y());
      bvh.triangles[i].v[k][2] = static_cast<float>(p.z());
      bvh.triangles[i].v[k][3] = 0;
    }
  }
  // Broad-phase sphere: centred on the root box, through the farthest vertex.
  const BvhNode& root = bvh.nodes[0];
  const Eigen::Vector3d c(root.center[0], root.center[1], root.center[2]);
  double radius = 0;
  for (const Eigen::Vector3d& p : corners) radius = std::max(radius, (p - c).norm());
  for (int k = 0; k < 3; ++k) bvh.sphere_center[k] = root.center[k];
  bvh.sphere_radius = static_cast<float>(radius * (1 + 1e-6) + 1e-6 * c.norm());
  return bvh;
}

}  // namespace gplanner
