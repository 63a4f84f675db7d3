#pragma once
// Bounding-volume hierarchies of oriented boxes over triangle meshes, built on the CPU
// and stored flat (16-byte aligned, children side by side) for coalesced loads on the
// GPU. One BVH per rigid body: each robot link, and the static environment.

#include <cstdint>
#include <vector>

#include "gplanner/collision_gpu/geometry/obb.h"

namespace gplanner {

// 80 bytes (72 used, padded to 16-byte alignment). Inner nodes have children at `child`
// and `child + 1`; a leaf holds one triangle, encoded as child = -(triangle + 1).
struct alignas(16) BvhNode {
  float center[3];
  std::int32_t child;
  float axes[9];  // row-major; the columns are the box's unit axes
  float extent[3];
  float radius;  // |extent|: the box's bounding sphere about its centre, for a cheap first test
  // Inner nodes: where the children part along the box's first axis (column 0 of axes),
  // in the body's frame: `child` holds the triangles whose centroids lie at or below it,
  // `child + 1` those at or above. Lets a traversal order the children without loading
  // them.
  float split;

  GP_HD bool is_leaf() const { return child < 0; }
  GP_HD int triangle() const { return -child - 1; }
};

// A triangle's three vertices, padded to 16-byte rows (48 bytes).
struct alignas(16) BvhTriangle {
  float v[3][4];
};

struct Bvh {
  std::vector<BvhNode> nodes;          // nodes[0] is the root (empty: no geometry)
  std::vector<BvhTriangle> triangles;  // in leaf order
  // A sphere around every triangle, for the broad phase.
  float sphere_center[3] = {0, 0, 0};
  float sphere_radius = 0;

  bool empty() const { return nodes.empty(); }
};

// Builds the BVH of a triangle mesh. vertices: shape [vertex_count, 3]; triangles:
// shape [triangle_count, 3] (vertex indices). Boxes are fitted to the vertices' principal
// axes and split at the mean triangle centroid along the widest axis (as FCL's OBB trees
// are), or at the median where the mean leaves under a quarter on one side, so the
// depth stays within log(triangle_count) / log(4/3); computed in double and rounded
// outward to float.
Bvh build_bvh(const double* vertices, int vertex_count, const int* triangles, int triangle_count);

// The node's box as a geometry type.
GP_HD geometry::Obb<float> node_box(const BvhNode& node) {
  geometry::Obb<float> box;
  box.center = {node.center[0], node.center[1], node.center[2]};
  for (int i = 0; i < 3; ++i)
    box.axes.r[i] = {node.axes[3 * i], node.axes[3 * i + 1], node.axes[3 * i + 2]};
  box.extent = {node.extent[0], node.extent[1], node.extent[2]};
  return box;
}

}  // namespace gplanner
