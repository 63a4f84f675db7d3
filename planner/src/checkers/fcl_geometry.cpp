#include "fcl_geometry.h"

#include <vector>

namespace gplanner::internal {

std::shared_ptr<FclBvh> fcl_mesh(const TriangleMesh& mesh) {
  auto bvh = std::make_shared<FclBvh>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices.size()));
  bvh->addSubModel(mesh.vertices, triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

std::shared_ptr<fcl::CollisionGeometryd> fcl_primitive(const Obstacle& obstacle) {
  const Eigen::Vector3d& d = obstacle.dimensions;
  if (!obstacle.is_solid_round_primitive()) return nullptr;
  switch (obstacle.shape) {
    case ObstacleShape::kSphere:
      return std::make_shared<fcl::Sphered>(d.x());
    case ObstacleShape::kCylinder:
      return std::make_shared<fcl::Cylinderd>(d.x(), d.y());
    case ObstacleShape::kBox:
    case ObstacleShape::kMesh:
      break;
  }
  return nullptr;
}

}  // namespace gplanner::internal
