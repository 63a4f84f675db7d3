#pragma once
// Everything the batch checker needs about a scene, as flat arrays: the kinematic tree
// in topological order, one BVH per link and one for the environment, the link pairs
// to check against each other, the bodies' solid components, and the tolerance. Built
// once per scene by the planner (from URDF, SRDF and meshes) and uploaded once.

#include <cstdint>
#include <vector>

#include "gplanner/collision_gpu/bvh.h"
#include "gplanner/collision_gpu/solids.h"

namespace gplanner {

enum class BaseKind : std::int32_t { kFixed = 0, kPlanar = 1, kFloating = 2 };
enum class LinkMotion : std::int32_t { kFixed = 0, kRevolute = 1, kPrismatic = 2 };

// One link: how it moves relative to its parent. The joint value is
//   value = multiplier * (source >= 0 ? q[source] : 0) + offset,
// which covers planned joints (multiplier 1), fixed values (multiplier 0) and mimic
// joints following a planned or fixed master.
struct LinkKinematics {
  std::int32_t parent = -1;  // -1: the root, placed by the base
  LinkMotion motion = LinkMotion::kFixed;
  std::int32_t source = -1;  // configuration entry driving the joint, or -1
  float multiplier = 0;
  float offset = 0;
  float X_PJ[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};  // rotation (row-major), translation
  float axis[3] = {1, 0, 0};                              // unit, in the joint frame
};

struct CollisionModel {
  BaseKind base = BaseKind::kFixed;
  float X_WB[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};  // fixed base / plane of a planar base
  std::int32_t width = 0;                                 // floats per configuration
  std::vector<LinkKinematics> links;                      // parents before children
  std::vector<Bvh> link_bvhs;                             // per link (empty: no geometry)
  Bvh environment;                                        // in the world frame
  std::vector<std::int32_t> pair_a, pair_b;               // link pairs checked for self-collision
  // The connected components of each link and of the environment, for the containment
  // step (solids.h); a body without them is never inside anything nor holds anything.
  std::vector<std::vector<BodyComponent>> link_components;  // per link, or empty
  std::vector<BodyComponent> environment_components;
  // Leaf tests report triangles closer than this as colliding (half the tolerance band
  // delta, so that rounding stays inside the band); BV tests use a margin of twice it.
  float threshold = 0;

  std::size_t triangle_count() const;
};

}  // namespace gplanner
