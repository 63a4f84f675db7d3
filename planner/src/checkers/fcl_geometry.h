#pragma once
// Our geometry as FCL's (private to planner/src/checkers): the fcl backend and the
// collision report build the same models from a scene.

#include <fcl/fcl.h>

#include <memory>

#include "gplanner/planner/scene/scene.h"

namespace gplanner::internal {

using FclBvh = fcl::BVHModel<fcl::OBBRSSd>;

// A triangle mesh as an FCL BVH (OBBRSS, double).
std::shared_ptr<FclBvh> fcl_mesh(const TriangleMesh& mesh);

// A solid sphere or cylinder obstacle as FCL's own shape, as MoveIt checks them; null for
// any other (Obstacle::is_solid_round_primitive). A solid box is checked as its mesh, the
// 12 triangles, which are exact: FCL's GJK (GST_INDEP, FCL 0.7) misses box-triangle
// intersections up to a millimetre deep (docs/design.md, "Solids").
std::shared_ptr<fcl::CollisionGeometryd> fcl_primitive(const Obstacle& obstacle);

}  // namespace gplanner::internal
