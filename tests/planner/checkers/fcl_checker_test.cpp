// The FCL backend on cases whose answer is known by construction.

#include "gplanner/planner/checkers/fcl_checker.h"

#include <gtest/gtest.h>

#include <random>

#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

// A unit cube robot (rigid, floating) and a unit cube obstacle centred at the origin.
const char* kCubeObj =
    "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\nv 0.5 0.5 -0.5\n"
    "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv -0.5 0.5 0.5\nv 0.5 0.5 0.5\n"
    "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
    "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";

const char* kRigidScene = R"(name: cubes
robot: {mesh: cube.obj}
obstacles:
  - box: [1, 1, 1]
bounds: {min: [-5, -5, -5], max: [5, 5, 5]}
start: {base: {xyz: [-3, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [3, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
)";

// Two boxes on a hinge: link b (0.2 x 0.2 x 1, pointing up from the hinge at z = 1)
// swings about y; link a is a 0.2 x 0.2 x 1 post below the hinge, and c a block at
// x = 0.8, z = 0.5 that b hits when it swings down far enough. a-b are adjacent (not
// checked); b-c are checked, a-c are disabled by the SRDF.
const char* kHingeUrdf = R"(<robot name="hinge">
  <link name="a"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.2 0.2 1"/></geometry></collision></link>
  <link name="b"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.2 0.2 1"/></geometry></collision></link>
  <link name="c"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="hinge" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 1"/>
    <axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="mount" type="fixed"><parent link="a"/><child link="c"/><origin xyz="0.8 0 0.5"/></joint>
</robot>
)";
const char* kHingeSrdf =
    R"(<robot name="hinge"><disable_collisions link1="a" link2="c" reason="Adjacent"/></robot>)";
const char* kHingeScene = R"(name: hinge
robot: {urdf: hinge.urdf, srdf: hinge.srdf, planned_joints: [hinge]}
start: {joints: {hinge: 0}}
goal: {joints: {hinge: -1}}
)";

class FclCheckerTest : public ::testing::Test {
 protected:
  Scene rigid_scene() {
    scratch_.write("cube.obj", kCubeObj);
    return load_scene(scratch_.write("cubes.yaml", kRigidScene));
  }
  testing::ScratchFolder scratch_;
};

std::vector<float> at_x(double x) { return {float(x), 0, 0, 1, 0, 0, 0}; }

TEST_F(FclCheckerTest, SeparatedAndPenetratingCubes) {
  const Scene scene = rigid_scene();
  FclChecker checker(scene, 2);
  EXPECT_EQ(checker.backend(), "fcl");
  for (const double gap : {1e-1, 1e-2, 1e-3, 1e-4}) {
    EXPECT_FALSE(checker.in_collision(at_x(1 + gap).data())) << "gap " << gap;
    EXPECT_TRUE(checker.in_collision(at_x(1 - gap).data())) << "overlap " << gap;
    double distance = -1;
    checker.distance(at_x(1 + gap).data(), 1, &distance);
    EXPECT_NEAR(distance, gap, 1e-6) << "gap " << gap;
  }
  double inside = -1;
  checker.distance(at_x(0.5).data(), 1, &inside);
  EXPECT_EQ(inside, 0.0);
  // Rotated by 45 degrees about z the cube reaches sqrt(2)/2 from its centre.
  const double c = std::cos(M_PI / 8), s = std::sin(M_PI / 8);
  const std::vector<float> turned_free = {
      float(0.5 + std::sqrt(0.5) + 1e-3), 0, 0, float(c), 0, 0, float(s)};
  const std::vector<float> turned_hit = {
      float(0.5 + std::sqrt(0.5) - 1e-3), 0, 0, float(c), 0, 0, float(s)};
  EXPECT_FALSE(checker.in_collision(turned_free.data()));
  EXPECT_TRUE(checker.in_collision(turned_hit.data()));
}

TEST_F(FclCheckerTest, VerdictsDoNotDependOnThreadCount) {
  const Scene scene = rigid_scene();
  const int n = 3000, width = scene.space.width();
  const std::vector<float> q = testing::sample_configurations(scene, n, 11);
  FclChecker one(scene, 1), four(scene, 4);
  std::vector<std::uint8_t> a(n), b(n);
  one.check(q.data(), n, a.data());
  four.check(q.data(), n, b.data());
  EXPECT_EQ(a, b);
  // Cross-check each verdict against the geometry: two unit cubes collide exactly when
  // the robot's centre is within 1/2 + (its support radius) of the origin; outside the
  // circumscribed distance they are always free, inside the inscribed one always hit.
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const double r = Eigen::Vector3d(q[i * width], q[i * width + 1], q[i * width + 2]).norm();
    if (r > 2 * std::sqrt(3.0) / 2 + 1e-6) EXPECT_EQ(a[i], 0) << "far apart at " << r;
    if (r < 1.0 - 1e-6) EXPECT_EQ(a[i], 1) << "centres within 1 at " << r;
    hits += a[i];
  }
  EXPECT_GT(hits, 0);
  EXPECT_LT(hits, n);
}

TEST_F(FclCheckerTest, SelfCollisionOfCheckedPairsOnly) {
  scratch_.write("hinge.urdf", kHingeUrdf);
  scratch_.write("hinge.srdf", kHingeSrdf);
  const Scene scene = load_scene(scratch_.write("hinge.yaml", kHingeScene));
  const auto pairs = scene.robot.checked_pairs();
  ASSERT_EQ(pairs.size(), 1u);  // only b-c: a-b adjacent, a-c disabled
  EXPECT_EQ(scene.robot.links[pairs[0].first].name, "b");
  EXPECT_EQ(scene.robot.links[pairs[0].second].name, "c");
  FclChecker checker(scene, 1);
  // Swinging b about y by angle t turns its axis to (sin t, 0, cos t) from the hinge at
  // z = 1; block c spans x in [0.7, 0.9], z in [0.4, 0.6]. At t = 2 c's corner
  // (0.8, 0.6) lies 0.03 from b's axis, inside b's half-width of 0.1; at t = 1 b is
  // still above c. The post a is never checked against b.
  const float upright = 0, tilted = 1.0f, down = 2.0f;
  EXPECT_FALSE(checker.in_collision(&upright));
  EXPECT_FALSE(checker.in_collision(&tilted));
  EXPECT_TRUE(checker.in_collision(&down));
  const float backwards = -2.5f;  // b swings down the other side, into the post's side only
  EXPECT_FALSE(checker.in_collision(&backwards));
  double clearance = -1;
  checker.distance(&upright, 1, &clearance);
  // Upright, b's corner (0.1, 1) is nearest c's corner (0.7, 0.6).
  EXPECT_NEAR(clearance, std::sqrt(0.6 * 0.6 + 0.4 * 0.4), 1e-6);
  check_start_and_goal(scene, &checker);
}

}  // namespace
}  // namespace gplanner
