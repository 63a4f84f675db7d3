#include "gplanner/planner/scene/scene_collision_model.h"

#include <algorithm>
#include <cmath>

namespace gplanner {
namespace {

void store_transform(const Eigen::Isometry3d& X, float* out) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out[3 * i + j] = static_cast<float>(X.linear()(i, j));
    out[9 + i] = static_cast<float>(X.translation()[i]);
  }
}

Bvh mesh_bvh(const TriangleMesh& mesh) {
  std::vector<double> vertices;
  vertices.reserve(3 * mesh.vertices.size());
  for (const Eigen::Vector3d& p : mesh.vertices)
    vertices.insert(vertices.end(), {p.x(), p.y(), p.z()});
  std::vector<int> triangles;
  triangles.reserve(3 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    triangles.insert(triangles.end(), {t[0], t[1], t[2]});
  return build_bvh(vertices.data(), static_cast<int>(mesh.vertices.size()), triangles.data(),
                   static_cast<int>(mesh.triangles.size()));
}

// The largest absolute value joint j takes within the scene.
double joint_magnitude(const RobotModel& robot, const ConfigurationSpace& space, int j) {
  const Joint& joint = robot.joints[j];
  const int master = joint.mimic_joint >= 0 ? joint.mimic_joint : j;
  double lo = space.fixed_positions[master], hi = lo;
  for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
    if (space.planned_joints[i] == master) {
      lo = space.lower[i];
      hi = space.upper[i];
    }
  }
  if (joint.mimic_joint >= 0) {
    lo = joint.mimic_multiplier * lo + joint.mimic_offset;
    hi = joint.mimic_multiplier * hi + joint.mimic_offset;
  }
  return std::max(std::abs(lo), std::abs(hi));
}

}  // namespace

double tolerance_delta(const Scene& scene) {
  return scene.planner.number("delta_fraction") * scene.bounds_S().diagonal().norm();
}

double robot_reach(const RobotModel& robot, const ConfigurationSpace& space) {
  std::vector<double> origin_reach(robot.links.size(), 0.0);
  double reach = 0;
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    if (robot.links[l].parent_joint >= 0) {
      const int j = robot.links[l].parent_joint;
      const Joint& joint = robot.joints[j];
      origin_reach[l] = origin_reach[joint.parent_link] + joint.X_PJ.translation().norm();
      if (joint.type == JointType::kPrismatic) origin_reach[l] += joint_magnitude(robot, space, j);
    }
    double extent = 0;
    for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
      extent = std::max(extent, p.norm());
    reach = std::max(reach, origin_reach[l] + extent);
  }
  return reach;
}

std::size_t drop_unreachable_obstacle_triangles(Scene* scene) {
  const ConfigurationSpace& space = scene->space;
  const double reach = robot_reach(scene->robot, space);
  // Where the root's origin can be.
  const Eigen::AlignedBox3d base_region = space.base_region();
  // Grow by the reach, plus a margin well beyond the tolerance band.
  const double grow = reach * (1 + 1e-6) + 1e-3;
  const Eigen::AlignedBox3d region(base_region.min().array() - grow,
                                   base_region.max().array() + grow);
  std::size_t dropped = 0;
  for (Obstacle& obstacle : scene->obstacles) {
    std::vector<Eigen::Vector3i> kept;
    for (const Eigen::Vector3i& t : obstacle.mesh_S.triangles) {
      Eigen::AlignedBox3d box;
      for (int k = 0; k < 3; ++k) box.extend(obstacle.mesh_S.vertices[t[k]]);
      if (box.intersects(region)) kept.push_back(t);
    }
    dropped += obstacle.mesh_S.triangles.size() - kept.size();
    obstacle.mesh_S.triangles = std::move(kept);
  }
  scene->obstacles.erase(std::remove_if(scene->obstacles.begin(), scene->obstacles.end(),
                                        [](const Obstacle& o) { return o.mesh_S.empty(); }),
                         scene->obstacles.end());
  return dropped;
}

CollisionModel build_collision_model(const Scene& scene) {
  const RobotModel& robot = scene.robot;
  const ConfigurationSpace& space = scene.space;
  CollisionModel model;
  model.base = space.base == BaseType::kFloating ? BaseKind::kFloating
               : space.base == BaseType::kPlanar ? BaseKind::kPlanar
                                                 : BaseKind::kFixed;
  store_transform(space.X_SB, model.X_WB);  // the core's W is our S
  model.width = space.width();
  model.threshold = static_cast<float>(tolerance_delta(scene) / 2);

  // Configuration entry of each planned joint.
  std::vector<int> entry(robot.joints.size(), -1);
  for (std::size_t i = 0; i < space.planned_joints.size(); ++i) {
    entry[space.planned_joints[i]] = space.base_width() + static_cast<int>(i);
  }
  for (const Link& link : robot.links) {
    LinkKinematics k;
    if (link.parent_joint >= 0) {
      const Joint& joint = robot.joints[link.parent_joint];
      k.parent = joint.parent_link;
      store_transform(joint.X_PJ, k.X_PJ);
      for (int c = 0; c < 3; ++c) k.axis[c] = static_cast<float>(joint.axis_J[c]);
      if (joint.is_single_dof()) {
        k.motion =
            joint.type == JointType::kPrismatic ? LinkMotion::kPrismatic : LinkMotion::kRevolute;
        // value = multiplier * q[source] + offset, folding in mimic and fixed values.
        const int master = joint.mimic_joint >= 0 ? joint.mimic_joint : link.parent_joint;
        const double m = joint.mimic_joint >= 0 ? joint.mimic_multiplier : 1.0;
        const double o = joint.mimic_joint >= 0 ? joint.mimic_offset : 0.0;
        if (entry[master] >= 0) {
          k.source = entry[master];
          k.multiplier = static_cast<float>(m);
          k.offset = static_cast<float>(o);
        } else {
          k.multiplier = 0;
          k.offset = static_cast<float>(m * space.fixed_positions[master] + o);
        }
      }
    }
    model.links.push_back(k);
    model.link_bvhs.push_back(mesh_bvh(link.collision));
  }
  model.environment = mesh_bvh(scene.environment_mesh());
  for (const auto& [a, b] : robot.checked_pairs()) {
    model.pair_a.push_back(a);
    model.pair_b.push_back(b);
  }
  return model;
}

}  // namespace gplanner
