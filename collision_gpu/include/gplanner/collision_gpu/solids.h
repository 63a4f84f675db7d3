#pragma once
// Solids (docs/design.md, "Solids"): the connected components of every body (each robot
// link, the environment), each a surface or, when closed, a solid; and what the
// containment step reads of them. When two bodies' surfaces do not come within the
// threshold, each component of one lies wholly inside or wholly outside each solid
// component of the other, so one point per component decides: a tree over each body's
// component points meets a tree over the other's solid components' boxes, and a point
// inside a box is tested by rays through that solid component's own BVH.

#include <cstdint>
#include <vector>

#include "gplanner/collision_gpu/bvh.h"

namespace gplanner {

// One connected component of a body's triangles, as the planner hands it over.
struct BodyComponent {
  float point[3] = {0, 0, 0};                            // one of its vertices, in the body's frame
  float box_min[3] = {0, 0, 0}, box_max[3] = {0, 0, 0};  // around its vertices
  Bvh solid;  // its own BVH when it is solid (closed); empty when it is a surface
};

// Builds a component from its triangles. vertices: shape [vertex_count, 3];
// triangles: shape [triangle_count, 3], indices into vertices (only the component's
// own triangles). The point is the first triangle's first vertex.
BodyComponent make_body_component(const double* vertices, int vertex_count, const int* triangles,
                                  int triangle_count, bool solid);

// A component as the containment step reads it (48 bytes).
struct alignas(16) Component {
  float point[3];                  // in the body's frame
  std::int32_t solid_node_offset;  // root of its BVH in SolidsView::nodes; -1: a surface
  float center[3];                 // its axis-aligned box, in the body's frame
  std::int32_t solid_triangle_offset;
  float extent[3];
  float pad;
};

// A node of a tree over components (32 bytes): an axis-aligned box in the body's frame;
// inner nodes have children at child and child + 1, a leaf holds the component
// -(child + 1) of SolidsView::components. size: in a tree over points, the least longest
// side of the boxes of the components below (no component below is smaller across); in
// a tree over solid boxes, the largest diagonal (none is larger). A component inside
// another is no larger, so a point subtree whose size exceeds a solid subtree's holds
// nothing inside it.
struct alignas(16) ComponentNode {
  float center[3];
  std::int32_t child;
  float extent[3];
  float size;

  GP_HD bool is_leaf() const { return child < 0; }
  GP_HD int component() const { return -child - 1; }
};

// Where one body's trees are; -1: none.
struct BodySolids {
  std::int32_t points = -1;  // root of the tree over the points of all its components
  std::int32_t solids = -1;  // root of the tree over the boxes of its solid components
};

// Kept small: a part of the view passed by value into kernels.
struct SolidsView {
  const Component* components;
  const ComponentNode* tree;
  const BvhNode* nodes;  // the solid components' BVHs
  const BvhTriangle* triangles;
};

// Host-side flat arrays of the components of several bodies.
class FlatSolids {
 public:
  // Appends a body's components and builds its two trees.
  BodySolids add_body(const std::vector<BodyComponent>& components);

  SolidsView view() const;  // pointers into this object's vectors

  std::vector<Component> components;
  std::vector<ComponentNode> tree;
  std::vector<BvhNode> nodes;
  std::vector<BvhTriangle> triangles;
  // Deepest tree (root: 1) and deepest solid component BVH: the containment step's
  // stacks are sized from them.
  int deepest_tree = 0;
  int deepest_bvh = 0;
};

// The containment rule of the collision core, on the host in double (docs/design.md,
// "Solids"): whether a component of body a lies inside a solid component of body b, or
// one of b inside a solid of a, b posed in a's frame by X_AB (row-major rotation R_AB
// and translation p_AB), their surfaces already known to be apart. For host checkers
// that apply the same rule (the fcl backend).
bool either_body_inside(const SolidsView& view, const BodySolids& a, const BodySolids& b,
                        const double R_AB[3][3], const double p_AB[3], double margin);

}  // namespace gplanner
