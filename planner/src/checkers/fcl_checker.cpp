#include "gplanner/planner/checkers/fcl_checker.h"

#include <fcl/fcl.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fcl_geometry.h"
#include "gplanner/collision_gpu/solids.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/common/scratch_pool.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {
namespace {

using internal::fcl_primitive;
using internal::FclBvh;

// Whether a component of one body lies inside a solid of the other, b posed in a's
// frame by X_AB: the collision core's rule (collision_gpu/solids.h).
bool either_inside(const SolidsView& view, const BodySolids& a, const BodySolids& b,
                   const Eigen::Isometry3d& X_AB, double margin) {
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = X_AB.linear()(i, j);
  const Eigen::Vector3d p = X_AB.translation();
  const double t[3] = {p.x(), p.y(), p.z()};
  return either_body_inside(view, a, b, R, t, margin);
}

// What one call needs to answer queries on one thread: its own collision objects (FCL
// objects carry their pose) over the shared, read-only BVHs and shapes.
struct Workspace {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> links;  // null for links without geometry
  std::unique_ptr<fcl::CollisionObjectd> environment;         // the mesh obstacles
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> primitives;
  std::vector<double> joint_positions;
  std::vector<Eigen::Isometry3d> X_WL;
};

// The distance between two axis-aligned boxes (0 where they overlap).
double box_distance(const fcl::AABBd& a, const fcl::AABBd& b) {
  double squared = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, a.min_[k] - b.max_[k], b.min_[k] - a.max_[k]});
    squared += gap * gap;
  }
  return std::sqrt(squared);
}

}  // namespace

struct FclChecker::Impl {
  const Scene& scene;
  int threads;
  std::vector<std::shared_ptr<FclBvh>> link_bvhs;
  std::shared_ptr<FclBvh> environment_bvh;
  // Solid sphere and cylinder obstacles: FCL's shapes, their poses in S, their
  // allowances, and whether GJK's answer of no contact takes a second opinion (below).
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> primitives;
  std::vector<Eigen::Isometry3d> X_SP;
  std::vector<double> allowances;
  std::vector<bool> second_opinion;
  // The containment rule of the collision core (detail/containment.h), on the same
  // components (the solid spheres and cylinders as their centres: FCL's shapes are solid
  // already), in double from FCL's own poses.
  FlatSolids solids;
  std::vector<BodySolids> link_solids;
  BodySolids environment_solids;
  bool containment = false;
  double margin = 0;
  double gjk_tolerance = 1e-6;
  std::vector<int> links_with_geometry;
  std::vector<std::pair<int, int>> checked_pairs;
  std::vector<int> pair_ancestors;  // per checked pair: RobotModel::deepest_common_link
  // Made in the constructor, and copied for each new workspace: FCL's constructor of a
  // collision object writes its geometry's local box, which other threads read.
  Workspace prototype;
  // Taken by each chunk of a call, so that calls from any number of threads run at once.
  ScratchPool<Workspace> workspaces{[this] { return copy_of_prototype(); }};

  // FCL sees the scene frame S (Scene::p_WS), as our collision core does, so the two
  // are compared like for like. It stays the ground truth: S is the world translated by
  // -p_WS, an isometry, under which no distance or intersection changes; the only
  // difference is that obstacle vertices were rounded once, in double, when made
  // relative to p_WS at load (by at most half an ulp of the world coordinate: 7e-12 m
  // at 1e5 m, against a band of 1e-5 of the scene's size). Rows hold poses in S to
  // begin with; in world coordinates the row's float could not place the robot within
  // the band at all.
  Impl(const Scene& s, int requested_threads)
      : scene(s), threads(resolve_thread_count(requested_threads)) {
    const RobotModel& robot = scene.robot;
    link_bvhs.resize(robot.links.size());
    for (std::size_t l = 0; l < robot.links.size(); ++l) {
      if (robot.links[l].collision.empty()) continue;
      link_bvhs[l] = internal::fcl_mesh(robot.links[l].collision);
      links_with_geometry.push_back(static_cast<int>(l));
    }
    TriangleMesh environment;
    for (const Obstacle& obstacle : scene.obstacles) {
      if (obstacle.is_solid_round_primitive()) {
        primitives.push_back(fcl_primitive(obstacle));
        X_SP.push_back(obstacle.X_SO);
        allowances.push_back(obstacle.allowance_m);
        second_opinion.push_back(obstacle.shape == ObstacleShape::kCylinder);
      } else {  // meshes, and solid boxes as their 12 exact triangles
        environment.append(obstacle.mesh_S);
      }
    }
    if (!environment.empty()) environment_bvh = internal::fcl_mesh(environment);
    checked_pairs = robot.checked_pairs();
    for (const auto& [a, b] : checked_pairs)
      pair_ancestors.push_back(robot.deepest_common_link(a, b));

    for (const Link& link : robot.links)
      link_solids.push_back(
          solids.add_body(mesh_body_components(link.collision, link_solid_triangles(link))));
    environment_solids = solids.add_body(environment_components(scene, true));
    const auto either_holds = [](BodySolids a, BodySolids b) {
      return (a.solids >= 0 && b.points >= 0) || (b.solids >= 0 && a.points >= 0);
    };
    for (int l : links_with_geometry)
      containment = containment || either_holds(link_solids[l], environment_solids);
    for (const auto& [a, b] : checked_pairs)
      containment = containment || either_holds(link_solids[a], link_solids[b]);
    margin = tolerance_delta(scene);
    gjk_tolerance = std::min(1e-6, margin / 100);

    prototype.links.resize(robot.links.size());
    for (int l : links_with_geometry) {
      prototype.links[l] = std::make_unique<fcl::CollisionObjectd>(link_bvhs[l]);
    }
    if (environment_bvh) {
      prototype.environment = std::make_unique<fcl::CollisionObjectd>(environment_bvh);
      prototype.environment->computeAABB();
    }
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      prototype.primitives.push_back(
          std::make_unique<fcl::CollisionObjectd>(primitives[i], X_SP[i]));
      prototype.primitives.back()->computeAABB();
    }
    prototype.joint_positions.resize(robot.joints.size());
  }

  // Copies only read the prototype (and the shared BVHs' reference counts).
  std::unique_ptr<Workspace> copy_of_prototype() const {
    auto w = std::make_unique<Workspace>();
    w->links.resize(prototype.links.size());
    for (int l : links_with_geometry) {
      w->links[l] = std::make_unique<fcl::CollisionObjectd>(*prototype.links[l]);
    }
    if (prototype.environment) {
      w->environment = std::make_unique<fcl::CollisionObjectd>(*prototype.environment);
    }
    for (const auto& primitive : prototype.primitives)
      w->primitives.push_back(std::make_unique<fcl::CollisionObjectd>(*primitive));
    w->joint_positions = prototype.joint_positions;
    return w;
  }

  // Poses every link object for configuration q.
  void pose_links(const float* q, Workspace* w) const {
    const ConfigurationSpace& space = scene.space;
    const Eigen::Isometry3d X_SR = space.base_pose(q);  // "W" below is the scene frame
    if (scene.robot.links.size() == 1) {
      w->X_WL.assign(1, X_SR);  // a rigid body: no kinematics
    } else {
      space.joint_positions(scene.robot, q, w->joint_positions.data());
      forward_kinematics(scene.robot, X_SR, w->joint_positions.data(), &w->X_WL);
    }
    for (int l : links_with_geometry) {
      w->links[l]->setTransform(w->X_WL[l]);
      w->links[l]->computeAABB();
    }
  }

  // Whether row q is a configuration at all: every entry finite and, for a floating
  // base, a quaternion of non-zero length (Eigen would read a zero one as no turn).
  // Rows that are not are reported colliding, as the collision core does.
  bool is_configuration(const float* q) const {
    const ConfigurationSpace& space = scene.space;
    for (int k = 0; k < space.width(); ++k)
      if (!std::isfinite(q[k])) return false;
    return space.base != BaseType::kFloating || q[3] != 0 || q[4] != 0 || q[5] != 0 || q[6] != 0;
  }

  bool collides(const float* q, Workspace* w) const {
    if (!is_configuration(q)) return true;
    pose_links(q, w);
    fcl::CollisionRequestd request;  // one contact is enough for a verdict
    // The primitives go through GJK, whose tolerance is absolute (1e-6 m by default: in a
    // scene a few millimetres wide, many bands); a hundredth of the band instead, with
    // FCL's own GJK (libccd's reported gaps of a few bands colliding in
    // tests/stability/coplanar_test.cpp's millimetre scenes, FCL's own within 0.01 delta).
    request.gjk_tolerance = gjk_tolerance;
    request.gjk_solver_type = fcl::GST_INDEP;
    // A cylinder meets triangles through GJK alone (FCL has no exact test for the pair),
    // and FCL's GJK now and then finds no contact where a triangle lies millimetres
    // inside (tests/planner/checkers/fcl_checker_test.cpp): where it finds none, libccd's
    // GJK is asked too, and a contact found by either counts. (Spheres have FCL's exact
    // sphere-triangle test; boxes are checked as their triangles.)
    fcl::CollisionRequestd second_request = request;
    second_request.gjk_solver_type = fcl::GST_LIBCCD;
    const auto touch = [&](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b,
                           bool ask_twice = false) {
      if (!a->getAABB().overlap(b->getAABB())) return false;
      fcl::CollisionResultd result;
      if (fcl::collide(a, b, request, result) > 0) return true;
      fcl::CollisionResultd second;
      return ask_twice && fcl::collide(a, b, second_request, second) > 0;
    };
    for (int l : links_with_geometry) {
      if (w->environment && touch(w->links[l].get(), w->environment.get())) return true;
      for (std::size_t i = 0; i < w->primitives.size(); ++i)
        if (touch(w->links[l].get(), w->primitives[i].get(), second_opinion[i])) return true;
    }
    for (const auto& [a, b] : checked_pairs) {
      if (touch(w->links[a].get(), w->links[b].get())) return true;
    }
    return contained(*w);
  }

  // After no surfaces met: the core's containment rule on the same components, with
  // FCL's double poses (docs/design.md, "Solids").
  bool contained(const Workspace& w) const {
    if (!containment) return false;
    const SolidsView view = solids.view();
    for (int l : links_with_geometry) {
      if (either_inside(view, environment_solids, link_solids[l], w.X_WL[l], margin)) return true;
    }
    for (const auto& [a, b] : checked_pairs) {
      if (either_inside(view, link_solids[a], link_solids[b], w.X_WL[a].inverse() * w.X_WL[b],
                        margin))
        return true;
    }
    return false;
  }

  double distance(const float* q, Workspace* w) const {
    if (collides(q, w)) return 0;
    double smallest = std::numeric_limits<double>::infinity();
    fcl::DistanceRequestd request;
    request.distance_tolerance = gjk_tolerance;
    request.gjk_solver_type = fcl::GST_INDEP;
    auto measure = [&](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b) {
      fcl::DistanceResultd result;
      result.min_distance = smallest;
      fcl::distance(a, b, request, result);
      smallest = std::min(smallest, std::max(0.0, result.min_distance));
    };
    for (int l : links_with_geometry) {
      if (w->environment) measure(w->links[l].get(), w->environment.get());
    }
    // A primitive whose tessellation lies outside it by more than the band: its
    // distance less that allowance (Obstacle::allowance_m).
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      for (int l : links_with_geometry) {
        fcl::DistanceResultd result;
        result.min_distance = smallest + allowances[i];
        fcl::distance(w->links[l].get(), w->primitives[i].get(), request, result);
        smallest = std::min(smallest, std::max(0.0, result.min_distance - allowances[i]));
      }
    }
    for (const auto& [a, b] : checked_pairs) measure(w->links[a].get(), w->links[b].get());
    return smallest;
  }

  // Whether the configuration collides, or some body comes closer than its clearance
  // (CollisionChecker::check_clearances; c: the row's clearances, one per robot link), its
  // clearance raised by `slack`.
  bool closer_than(const float* q, const float* c, double slack, Workspace* w) const {
    for (std::size_t l = 0; l < scene.robot.links.size(); ++l)
      if (!(c[l] >= 0)) return true;  // not a number: never free
    if (collides(q, w)) return true;
    fcl::DistanceRequestd request;
    request.distance_tolerance = gjk_tolerance;
    request.gjk_solver_type = fcl::GST_INDEP;
    const auto closer = [&](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, double clearance,
                            double allowance) {
      if (!(clearance + slack > 0)) return false;  // collides() said they do not touch
      // Boxes apart by the clearance: the bodies are (FCL's distance is at least the
      // boxes'); most body pairs end here, without the distance query.
      a->computeAABB();
      b->computeAABB();
      if (box_distance(a->getAABB(), b->getAABB()) - allowance >= std::max(0.0, clearance) + slack)
        return false;
      fcl::DistanceResultd result;
      fcl::distance(a, b, request, result);
      return result.min_distance - allowance < std::max(0.0, clearance) + slack;
    };
    for (int l : links_with_geometry) {
      if (w->environment && closer(w->links[l].get(), w->environment.get(), c[l], 0)) return true;
      for (std::size_t i = 0; i < primitives.size(); ++i)
        if (closer(w->links[l].get(), w->primitives[i].get(), c[l], allowances[i])) return true;
    }
    for (std::size_t p = 0; p < checked_pairs.size(); ++p) {
      const auto [a, b] = checked_pairs[p];
      const double clearance = double(c[a]) + c[b] - 2.0 * c[pair_ancestors[p]];
      if (closer(w->links[a].get(), w->links[b].get(), clearance, 0)) return true;
    }
    return false;
  }
};

FclChecker::FclChecker(const Scene& scene, int threads)
    : impl_(std::make_unique<Impl>(scene, threads)) {}

FclChecker::~FclChecker() = default;

int FclChecker::threads() const { return impl_->threads; }

void FclChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  const std::size_t width = impl_->scene.space.width();
  parallel_for(n, impl_->threads, [&](std::size_t begin, std::size_t end, int) {
    const auto w = impl_->workspaces.take();
    for (std::size_t i = begin; i < end; ++i) {
      verdicts[i] = impl_->collides(configurations + i * width, &*w) ? 1 : 0;
    }
  });
}

void FclChecker::check_clearances(const float* configurations, std::size_t n,
                                  const float* clearances, std::uint8_t* verdicts) {
  check_clearances(configurations, n, clearances, 0.0, verdicts);
}

void FclChecker::check_clearances(const float* configurations, std::size_t n,
                                  const float* clearances, double slack, std::uint8_t* verdicts) {
  const std::size_t width = impl_->scene.space.width();
  const std::size_t links = impl_->scene.robot.links.size();
  parallel_for(
      n, impl_->threads,
      [&](std::size_t begin, std::size_t end, int) {
        const auto w = impl_->workspaces.take();
        for (std::size_t i = begin; i < end; ++i) {
          verdicts[i] =
              impl_->closer_than(configurations + i * width, clearances + i * links, slack, &*w)
                  ? 1
                  : 0;
        }
      },
      1);
}

void FclChecker::distance(const float* configurations, std::size_t n, double* distances) {
  const std::size_t width = impl_->scene.space.width();
  parallel_for(
      n, impl_->threads,
      [&](std::size_t begin, std::size_t end, int) {
        const auto w = impl_->workspaces.take();
        for (std::size_t i = begin; i < end; ++i) {
          distances[i] = impl_->distance(configurations + i * width, &*w);
        }
      },
      1);
}

}  // namespace gplanner
