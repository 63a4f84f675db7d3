#include "gplanner/planner/checkers/fcl_checker.h"

#include <fcl/fcl.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gplanner/common/parallel_for.h"
#include "gplanner/common/scratch_pool.h"
#include "gplanner/planner/scene/forward_kinematics.h"

namespace gplanner {
namespace {

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<Bvh> build_bvh(const TriangleMesh& mesh) {
  auto bvh = std::make_shared<Bvh>();
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  bvh->beginModel(static_cast<int>(triangles.size()), static_cast<int>(mesh.vertices.size()));
  bvh->addSubModel(mesh.vertices, triangles);
  bvh->endModel();
  bvh->computeLocalAABB();
  return bvh;
}

// What one call needs to answer queries on one thread: its own collision objects (FCL
// objects carry their pose) over the shared, read-only BVHs.
struct Workspace {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> links;  // null for links without geometry
  std::unique_ptr<fcl::CollisionObjectd> environment;
  std::vector<double> joint_positions;
  std::vector<Eigen::Isometry3d> X_WL;
};

}  // namespace

struct FclChecker::Impl {
  const Scene& scene;
  int threads;
  std::vector<std::shared_ptr<Bvh>> link_bvhs;
  std::shared_ptr<Bvh> environment_bvh;
  std::vector<int> links_with_geometry;
  std::vector<std::pair<int, int>> checked_pairs;
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
      link_bvhs[l] = build_bvh(robot.links[l].collision);
      links_with_geometry.push_back(static_cast<int>(l));
    }
    const TriangleMesh environment = scene.environment_mesh();
    if (!environment.empty()) environment_bvh = build_bvh(environment);
    checked_pairs = robot.checked_pairs();
    prototype.links.resize(robot.links.size());
    for (int l : links_with_geometry) {
      prototype.links[l] = std::make_unique<fcl::CollisionObjectd>(link_bvhs[l]);
    }
    if (environment_bvh) {
      prototype.environment = std::make_unique<fcl::CollisionObjectd>(environment_bvh);
      prototype.environment->computeAABB();
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
    for (int l : links_with_geometry) {
      if (!w->environment || !w->links[l]->getAABB().overlap(w->environment->getAABB())) continue;
      fcl::CollisionResultd result;
      if (fcl::collide(w->links[l].get(), w->environment.get(), request, result) > 0) return true;
    }
    for (const auto& [a, b] : checked_pairs) {
      if (!w->links[a]->getAABB().overlap(w->links[b]->getAABB())) continue;
      fcl::CollisionResultd result;
      if (fcl::collide(w->links[a].get(), w->links[b].get(), request, result) > 0) return true;
    }
    return false;
  }

  double distance(const float* q, Workspace* w) const {
    if (collides(q, w)) return 0;
    double smallest = std::numeric_limits<double>::infinity();
    fcl::DistanceRequestd request;
    auto measure = [&](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b) {
      fcl::DistanceResultd result;
      result.min_distance = smallest;
      fcl::distance(a, b, request, result);
      smallest = std::min(smallest, std::max(0.0, result.min_distance));
    };
    for (int l : links_with_geometry) {
      if (w->environment) measure(w->links[l].get(), w->environment.get());
    }
    for (const auto& [a, b] : checked_pairs) measure(w->links[a].get(), w->links[b].get());
    return smallest;
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
