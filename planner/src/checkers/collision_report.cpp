#include "gplanner/planner/checkers/collision_report.h"

#include <fcl/fcl.h>

#include <limits>
#include <sstream>
#include <vector>

#include "fcl_geometry.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

using internal::fcl_mesh;
using internal::fcl_primitive;

std::string CollisionPair::describe() const {
  std::ostringstream text;
  if (found) {
    text << a << " and " << b;
  } else {
    text << "no surfaces meet (a link lies inside a closed body, or the verdict rests on the "
            "tolerance band); the closest are "
         << a << " and " << b << ", " << distance << " m apart";
  }
  return text.str();
}

struct CollisionReporter::Impl {
  const Scene& scene;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> links;  // null: no geometry
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> obstacles;
  std::vector<double> joint_positions;
  std::vector<Eigen::Isometry3d> X_SL;

  explicit Impl(const Scene& s) : scene(s), joint_positions(s.robot.joints.size()) {
    for (const Link& link : scene.robot.links) {
      links.push_back(link.collision.empty()
                          ? nullptr
                          : std::make_unique<fcl::CollisionObjectd>(fcl_mesh(link.collision)));
    }
    for (const Obstacle& obstacle : scene.obstacles) {
      obstacles.push_back(
          obstacle.is_solid_round_primitive()
              ? std::make_unique<fcl::CollisionObjectd>(fcl_primitive(obstacle), obstacle.X_SO)
              : std::make_unique<fcl::CollisionObjectd>(fcl_mesh(obstacle.mesh_S)));
      obstacles.back()->computeAABB();
    }
  }

  std::string link_text(int l) const { return "link '" + scene.robot.links[l].name + "'"; }
  std::string obstacle_key(std::size_t o) const { return "obstacles[" + std::to_string(o) + "]"; }
  std::string obstacle_text(std::size_t o) const {
    return "obstacle '" + scene.obstacles[o].name + "' (" + obstacle_key(o) + ")";
  }

  CollisionPair first_pair(const float* q) {
    const ConfigurationSpace& space = scene.space;
    space.joint_positions(scene.robot, q, joint_positions.data());
    forward_kinematics(scene.robot, space.base_pose(q), joint_positions.data(), &X_SL);
    for (std::size_t l = 0; l < links.size(); ++l) {
      if (!links[l]) continue;
      links[l]->setTransform(X_SL[l]);
      links[l]->computeAABB();
    }
    CollisionPair closest;
    closest.distance = std::numeric_limits<double>::infinity();
    // Measures one pair: true when it collides (then `closest` holds it).
    auto test = [&](fcl::CollisionObjectd* x, fcl::CollisionObjectd* y, std::string a,
                    std::string a_key, std::string b, std::string b_key) {
      fcl::CollisionRequestd request;
      fcl::CollisionResultd result;
      double distance = 0;
      if (fcl::collide(x, y, request, result) == 0) {
        fcl::DistanceRequestd distance_request;
        fcl::DistanceResultd distance_result;
        fcl::distance(x, y, distance_request, distance_result);
        distance = std::max(0.0, distance_result.min_distance);
        if (distance >= closest.distance) return false;
      }
      closest = {result.numContacts() > 0 || distance == 0,
                 std::move(a),
                 std::move(b),
                 std::move(a_key),
                 std::move(b_key),
                 distance};
      return closest.found;
    };
    for (std::size_t l = 0; l < links.size(); ++l) {
      if (!links[l]) continue;
      for (std::size_t o = 0; o < obstacles.size(); ++o) {
        if (test(links[l].get(), obstacles[o].get(), link_text(l), scene.robot.links[l].name,
                 obstacle_text(o), obstacle_key(o)))
          return closest;
      }
    }
    for (const auto& [a, b] : scene.robot.checked_pairs()) {
      if (test(links[a].get(), links[b].get(), link_text(a), scene.robot.links[a].name,
               link_text(b), scene.robot.links[b].name))
        return closest;
    }
    return closest;
  }
};

CollisionReporter::CollisionReporter(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}

CollisionReporter::~CollisionReporter() = default;

CollisionPair CollisionReporter::first_pair(const float* q) { return impl_->first_pair(q); }

}  // namespace gplanner
