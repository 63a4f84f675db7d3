// Stability: the float32 forward kinematics of the collision core over a chain of 24
// revolute links against double precision, judged by the tolerance band: every link's
// pose, and so every vertex, must land well within delta of where double puts it.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/collision_gpu/model_view.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr int kLinks = 24;

// A chain of kLinks boxes 0.25 m long, joints alternating about y and x, limits of a
// half turn either way: 6 m long when straight.
std::string chain_urdf() {
  std::ostringstream out;
  out << "<robot name=\"chain\">\n";
  for (int i = 0; i <= kLinks; ++i) {
    out << "<link name=\"l" << i << "\"><collision><origin xyz=\"0 0 0.125\"/><geometry>"
        << "<box size=\"0.08 0.08 0.25\"/></geometry></collision></link>\n";
  }
  for (int i = 1; i <= kLinks; ++i) {
    out << "<joint name=\"j" << i << "\" type=\"revolute\"><parent link=\"l" << i - 1
        << "\"/><child link=\"l" << i << "\"/><origin xyz=\"0 0 0.25\" rpy=\"0.01 0 0.02\"/>"
        << "<axis xyz=\"" << (i % 2 ? "0 1 0" : "1 0 0") << "\"/>"
        << "<limit lower=\"-3.1\" upper=\"3.1\" effort=\"1\" velocity=\"1\"/></joint>\n";
  }
  out << "</robot>\n";
  return out.str();
}

TEST(StabilityChains, FloatKinematicsOf24LinksStayWithinTheBand) {
  testing::ScratchFolder scratch;
  scratch.write("chain.urdf", chain_urdf());
  std::ostringstream joints, start, goal;
  for (int i = 1; i <= kLinks; ++i) {
    joints << (i > 1 ? ", " : "") << "j" << i;
    start << (i > 1 ? ", " : "") << "j" << i << ": 0";
    goal << (i > 1 ? ", " : "") << "j" << i << ": 0.1";
  }
  const Scene scene = load_scene(scratch.write(
      "scene.yaml", "name: chain\nrobot:\n  urdf: chain.urdf\n  planned_joints: [" + joints.str() +
                        "]\nobstacles:\n  - box: [0.5, 0.5, 0.5]\n    pose: {xyz: [5, 5, 5]}\n"
                        "start:\n  joints: {" +
                        start.str() + "}\ngoal:\n  joints: {" + goal.str() + "}\n"));
  const double delta = tolerance_delta(scene);
  const CollisionModel model = build_collision_model(scene);
  const FlatCollisionModel flat(model);
  const CollisionModelView view = flat.view();
  ASSERT_EQ(view.link_count, kLinks + 1);
  std::mt19937_64 rng(3);
  const int w = scene.space.width();
  std::vector<float> q(w);
  std::vector<double> positions(scene.robot.joints.size());
  std::vector<Eigen::Isometry3d> X_double;
  detail::Xf X_float[detail::kMaxLinks];
  double worst = 0;
  for (int trial = 0; trial < 500; ++trial) {
    scene.space.sample_uniform(&rng, q.data());
    detail::link_poses(view, q.data(), X_float);
    scene.space.joint_positions(scene.robot, q.data(), positions.data());
    forward_kinematics(scene.robot, scene.space.base_pose(q.data()), positions.data(), &X_double);
    for (int l = 0; l <= kLinks; ++l) {
      // The link's box corners under both: their distance bounds every vertex's error.
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d p((corner & 1) ? 0.04 : -0.04, (corner & 2) ? 0.04 : -0.04,
                                (corner & 4) ? 0.25 : 0.0);
        const detail::V3f f = X_float[l] * detail::V3f{float(p.x()), float(p.y()), float(p.z())};
        const Eigen::Vector3d d = X_double[l] * p;
        worst = std::max(worst, (Eigen::Vector3d(f.x, f.y, f.z) - d).norm());
      }
    }
  }
  std::cout << "largest vertex error of float kinematics over " << kLinks << " links: " << worst
            << " m; delta " << delta << " m\n";
  // The leaf test reports triangles within delta / 2 as colliding: the kinematics may
  // use at most a fifth of the band.
  EXPECT_LT(worst, delta / 5);
}

}  // namespace
}  // namespace gplanner
