#pragma once
// A CollisionModel flattened into a few arrays (all BVHs concatenated), and the small
// trivially-copyable view of it that traversal code takes by value, on host or device.

#include <cstdint>
#include <vector>

#include "gplanner/collision_gpu/collision_model.h"
#include "gplanner/collision_gpu/geometry/host_device.h"

namespace gplanner {

// Where one body's BVH lies in the concatenated arrays; node_offset < 0: no geometry.
struct BodyRange {
  std::int32_t node_offset = -1;
  std::int32_t triangle_offset = 0;
};

struct alignas(16) LinkSphere {
  float center[3];  // in the link frame
  float radius;
};

// Kept small: passed by value into kernels.
struct CollisionModelView {
  BaseKind base;
  float X_WB[12];
  std::int32_t width;
  float threshold;  // leaf test: triangles closer than this collide
  float margin;     // BV tests: boxes closer than this overlap
  std::int32_t link_count;
  const LinkKinematics* links;
  const BodyRange* link_bodies;
  const LinkSphere* link_spheres;
  BodyRange environment;
  const BvhNode* nodes;
  const BvhTriangle* triangles;
  std::int32_t pair_count;
  const std::int32_t* pair_a;
  const std::int32_t* pair_b;
  const std::int32_t* pair_ancestor;  // per pair: the deepest link both links hang from
  // Solids: whether any checked body pair has a solid component on either side (when
  // not, the containment step does nothing), and each body's component trees.
  std::int32_t containment;
  const BodySolids* link_solids;
  BodySolids environment_solids;
  SolidsView solids;
  // Clearances of a call (null: none), shape [queries, link_count], row i for query i of
  // the call (certified motions, planner/planning/certified_motions.h). Per query, c_l >= 0
  // for each link l, never smaller than its parent's. Link l is checked against the
  // environment with the leaf threshold raised by c_l, a checked pair (a, b) whose deepest
  // common ancestor link is h with it raised by c_a + c_b - 2 c_h (when c_l bounds how far
  // link l's points move in the world, c_a - c_h bounds how far a's move relative to h);
  // each body's BV margin is twice its threshold, as the model's own.
  const float* clearances;
};

// Query i's row of clearances, or null.
GP_HD const float* query_clearances(const CollisionModelView& m, long long i) {
  return m.clearances ? m.clearances + i * m.link_count : nullptr;
}

// Host-side flat arrays of a model: what the CPU backend reads, and what the GPU
// backend copies to the device as is.
struct FlatCollisionModel {
  explicit FlatCollisionModel(const CollisionModel& model);

  CollisionModelView view() const;  // pointers into this object's vectors

  BaseKind base;
  float X_WB[12];
  std::int32_t width;
  float threshold;
  std::vector<LinkKinematics> links;
  std::vector<BodyRange> link_bodies;
  std::vector<LinkSphere> link_spheres;
  BodyRange environment;
  std::vector<BvhNode> nodes;
  std::vector<BvhTriangle> triangles;
  std::vector<std::int32_t> pair_a, pair_b, pair_ancestor;
  FlatSolids solids;
  std::vector<BodySolids> link_solids;
  BodySolids environment_solids;
  bool containment = false;
  // Deepest node pair any traversal can reach: a link's BVH depth plus the deeper of the
  // links' and the environment's.
  int traversal_depth = 0;
};

// Deepest node of a BVH (root: 1); traversal stacks are sized from it.
int bvh_depth(const Bvh& bvh);

}  // namespace gplanner
