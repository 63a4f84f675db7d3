#include "gplanner/planner/scene/scene_collision_model.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/mesh_components.h"

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

ToleranceBand tolerance_band(const Scene& scene) {
  const RobotModel& robot = scene.robot;
  const ConfigurationSpace& space = scene.space;
  ToleranceBand band;
  // The scene: its obstacles, and everywhere the robot can be (a fixed base's reach
  // too, so that a robot with no obstacle in reach still has a size).
  Eigen::AlignedBox3d box = scene.bounds_S();
  const Eigen::AlignedBox3d base = space.base_region();
  band.reach = robot_reach(robot, space);
  box.extend((base.min().array() - band.reach).matrix());
  box.extend((base.max().array() + band.reach).matrix());
  band.scene_size = box.diagonal().norm();
  // The robot: its geometry at the start (any frame: only the box's size counts).
  if (scene.start.size() == static_cast<std::size_t>(space.width())) {
    std::vector<double> positions(robot.joints.size());
    space.joint_positions(robot, scene.start.data(), positions.data());
    std::vector<Eigen::Isometry3d> X_RL;
    forward_kinematics(robot, Eigen::Isometry3d::Identity(), positions.data(), &X_RL);
    Eigen::AlignedBox3d robot_box;
    for (std::size_t l = 0; l < robot.links.size(); ++l) {
      for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
        robot_box.extend(X_RL[l] * p);
    }
    if (!robot_box.isEmpty()) band.robot_size = robot_box.diagonal().norm();
  }
  band.delta = scene.planner.delta_fraction * band.scene_size;
  if (band.robot_size > 0 && kRobotBandFraction * band.robot_size < band.delta) {
    band.delta = kRobotBandFraction * band.robot_size;
    band.capped = true;
  }
  return band;
}

double tolerance_delta(const Scene& scene) { return tolerance_band(scene).delta; }

double largest_representable_coordinate(double delta) {
  return delta / 16 * 16777216.0;  // 2^24
}

void check_band_representable(const Scene& scene, const SourceLocation& robot_at,
                              const SourceLocation& bounds_at) {
  const ToleranceBand band = tolerance_band(scene);
  const double limit = largest_representable_coordinate(band.delta);
  const auto metres = [](double v) {
    std::ostringstream text;
    text << std::setprecision(3) << v << " m";
    return text.str();
  };
  const std::string why =
      "float cannot place it within the tolerance band, " + metres(band.delta) +
      (band.capped ? " (1e-3 of the robot's size)" : " (delta_fraction of the scene's size)") +
      ", which allows at most " + metres(limit);
  // Sizes first: an absurd obstacle or robot also moves the scene frame and everything
  // else far from it.
  for (const Obstacle& obstacle : scene.obstacles) {
    const double size = obstacle.mesh_S.bounds().diagonal().norm();
    if (!(size <= limit)) {
      throw InputError(obstacle.defined, "obstacle '" + obstacle.name + "' spans " + metres(size) +
                                             ": " + why +
                                             "; check its scale, or cut it to the region the "
                                             "robot can reach");
    }
  }
  const RobotModel& robot = scene.robot;
  const double reach = band.reach;
  if (!(reach <= limit)) {
    throw InputError(robot_at, "the robot reaches " + metres(reach) + " from its root: " + why +
                                   "; check its mesh scales and its prismatic joints' limits");
  }
  // A revolute joint's angle rounds to 2^-24 of itself in float, and moves the robot's
  // points by that times their distance, at most the reach.
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const JointType type = robot.joints[j].type;
    if (type != JointType::kRevolute && type != JointType::kContinuous) continue;
    const double angle = joint_magnitude(robot, scene.space, static_cast<int>(j));
    if (!(angle * reach <= limit)) {
      std::ostringstream text;
      text << "joint '" << robot.joints[j].name << "' turns to " << std::setprecision(3) << angle
           << " rad, where float rounds the robot's points (up to " << metres(reach)
           << " away) by more than the tolerance band allows (" << metres(band.delta)
           << "); give it limits within a few turns";
      throw InputError(robot_at, text.str());
    }
  }
  // Positions: everything within `limit` of the scene frame's origin.
  for (const Obstacle& obstacle : scene.obstacles) {
    double farthest = 0;
    for (const Eigen::Vector3d& p : obstacle.mesh_S.vertices)
      farthest = std::max(farthest, p.norm());
    if (!(farthest <= limit)) {
      throw InputError(obstacle.defined, "obstacle '" + obstacle.name + "' lies " +
                                             metres(farthest) + " from the scene's centre: " + why +
                                             "; cut it to the region the robot can reach");
    }
  }
  const Eigen::AlignedBox3d base = scene.space.base_region();
  const double farthest = std::max(base.min().norm(), base.max().norm()) + reach;
  if (!(farthest <= limit)) {
    throw InputError(bounds_at, "the robot can reach " + metres(farthest) +
                                    " from the scene's centre: " + why +
                                    "; give bounds around the region the robot works in");
  }
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

std::vector<std::uint8_t> link_solid_triangles(const Link& link) {
  if (link.solid.size() == link.collision.triangle_count()) return link.solid;
  return closed_triangles(mesh_components(link.collision));
}

std::vector<std::uint8_t> obstacle_solid_triangles(const Obstacle& obstacle) {
  if (obstacle.solid.size() == obstacle.mesh_S.triangle_count()) return obstacle.solid;
  return closed_triangles(mesh_components(obstacle.mesh_S));
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
    const TriangleMesh& mesh = obstacle.mesh_S;
    const std::vector<std::uint8_t> solid = obstacle_solid_triangles(obstacle);
    const MeshComponents components = mesh_components(mesh, solid);
    // A solid component is kept whole when its box meets the region: it may hold it.
    std::vector<Eigen::AlignedBox3d> solid_boxes(components.count);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (!solid[t]) continue;
      for (int k = 0; k < 3; ++k)
        solid_boxes[components.of_triangle[t]].extend(mesh.vertices[mesh.triangles[t][k]]);
    }
    std::vector<Eigen::Vector3i> kept;
    std::vector<std::uint8_t> kept_solid;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      Eigen::AlignedBox3d box;
      if (solid[t]) {
        box = solid_boxes[components.of_triangle[t]];
      } else {
        for (int k = 0; k < 3; ++k) box.extend(mesh.vertices[mesh.triangles[t][k]]);
      }
      if (!box.intersects(region)) continue;
      kept.push_back(mesh.triangles[t]);
      kept_solid.push_back(solid[t]);
    }
    dropped += mesh.triangles.size() - kept.size();
    obstacle.mesh_S.triangles = std::move(kept);
    obstacle.solid = std::move(kept_solid);
  }
  scene->obstacles.erase(std::remove_if(scene->obstacles.begin(), scene->obstacles.end(),
                                        [](const Obstacle& o) { return o.mesh_S.empty(); }),
                         scene->obstacles.end());
  return dropped;
}

std::vector<BodyComponent> mesh_body_components(const TriangleMesh& mesh,
                                                const std::vector<std::uint8_t>& solid) {
  std::vector<BodyComponent> out;
  if (mesh.empty()) return out;
  const MeshComponents components = mesh_components(mesh, solid);
  std::vector<std::vector<int>> triangles(components.count);
  std::vector<std::uint8_t> is_solid(components.count, 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int c = components.of_triangle[t];
    for (int k = 0; k < 3; ++k) triangles[c].push_back(mesh.triangles[t][k]);
    is_solid[c] = solid[t];
  }
  std::vector<double> vertices;
  vertices.reserve(3 * mesh.vertices.size());
  for (const Eigen::Vector3d& p : mesh.vertices)
    vertices.insert(vertices.end(), {p.x(), p.y(), p.z()});
  for (int c = 0; c < components.count; ++c) {
    out.push_back(make_body_component(vertices.data(), static_cast<int>(mesh.vertices.size()),
                                      triangles[c].data(),
                                      static_cast<int>(triangles[c].size() / 3), is_solid[c]));
  }
  return out;
}

std::vector<BodyComponent> environment_components(const Scene& scene, bool exact_round_primitives) {
  std::vector<BodyComponent> out;
  for (const Obstacle& obstacle : scene.obstacles) {
    if (exact_round_primitives && obstacle.is_solid_round_primitive()) {
      BodyComponent centre;
      const Eigen::Vector3d c = obstacle.X_SO.translation();
      const Eigen::AlignedBox3d box = obstacle.mesh_S.bounds();
      for (int k = 0; k < 3; ++k) {
        centre.point[k] = static_cast<float>(c[k]);
        centre.box_min[k] = static_cast<float>(box.min()[k]);
        centre.box_max[k] = static_cast<float>(box.max()[k]);
      }
      out.push_back(centre);
      continue;
    }
    std::vector<BodyComponent> parts =
        mesh_body_components(obstacle.mesh_S, obstacle_solid_triangles(obstacle));
    for (BodyComponent& part : parts) out.push_back(std::move(part));
  }
  return out;
}

void refine_primitive_obstacles(Scene* scene) {
  constexpr int kSphereSegments = 256, kCylinderSegments = 4096;
  const double kPi = std::acos(-1.0);
  const double target = tolerance_delta(*scene) / 5;
  const auto even_segments = [](double n, int most) {
    const int whole = static_cast<int>(std::ceil(std::min(n, double(most))));
    return std::max(24, whole + (whole & 1));
  };
  std::vector<std::pair<Obstacle*, double>> refined;  // and the excess of each
  for (Obstacle& obstacle : scene->obstacles) {
    if (!obstacle.is_solid_round_primitive()) continue;
    const double radius = obstacle.dimensions.x();
    TriangleMesh mesh;
    double excess = 0;
    if (obstacle.shape == ObstacleShape::kSphere) {
      // excess = radius * tan^2(pi / n) with n / 2 rings.
      int n = even_segments(kPi / std::atan(std::sqrt(target / radius)), kSphereSegments);
      while (n < kSphereSegments && sphere_tessellation_excess(radius, n / 2, n) > target) n += 2;
      mesh = make_sphere(radius, n / 2, n);
      excess = sphere_tessellation_excess(radius, n / 2, n);
    } else {
      int n = even_segments(kPi / std::acos(1 / (1 + target / radius)), kCylinderSegments);
      while (n < kCylinderSegments && cylinder_tessellation_excess(radius, n) > target) n += 2;
      mesh = make_cylinder(radius, obstacle.dimensions.y(), n);
      excess = cylinder_tessellation_excess(radius, n);
    }
    obstacle.mesh_S = transformed(mesh, obstacle.X_SO);
    obstacle.solid.assign(obstacle.mesh_S.triangle_count(), 1);
    refined.emplace_back(&obstacle, excess);
  }
  // The band again: the finer tessellations may have made the scene a little smaller.
  const double delta = tolerance_delta(*scene);
  for (auto [obstacle, excess] : refined) {
    if (excess <= delta / 4) continue;
    obstacle->allowance_m = excess;
    std::ostringstream notice;
    notice << std::setprecision(3) << "obstacle '" << obstacle->name << "' ("
           << obstacle->defined.file << ":" << obstacle->defined.line << "): the "
           << (obstacle->shape == ObstacleShape::kSphere ? "sphere" : "cylinder")
           << "'s tessellation lies up to " << excess
           << " m outside it, more than the tolerance band allows (" << delta
           << " m): the cpu and gpu backends may report a collision up to that far from it "
              "(gplan check --compare counts those within the band); give it as a mesh to "
              "choose its triangles";
    scene->notices.push_back(notice.str());
  }
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
  for (const Link& link : robot.links)
    model.link_components.push_back(
        mesh_body_components(link.collision, link_solid_triangles(link)));
  model.environment_components = environment_components(scene, false);
  for (const auto& [a, b] : robot.checked_pairs()) {
    model.pair_a.push_back(a);
    model.pair_b.push_back(b);
  }
  return model;
}

}  // namespace gplanner
