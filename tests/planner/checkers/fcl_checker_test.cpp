// The FCL backend on cases whose answer is known by construction.

#include "gplanner/planner/checkers/fcl_checker.h"

#include <gtest/gtest.h>

#include <fcl/fcl.h>

#include <random>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
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

// Where FCL's GJK is wrong. A robot of one triangle (a surface) against a solid box or
// cylinder, posed so that part of the triangle lies inside: cases that FCL's GJK solver
// (GST_INDEP, FCL 0.7) reports free, found on MotionBenchMaker's Panda (the box: link 5
// of the arm against a shelf 0.7 x 0.7 x 0.04, a point 0.39 mm inside) and among random triangles
// (the cylinder, a point 2.2 mm inside). The answer is known by construction: a point of the
// triangle lies inside the shape. The fcl backend checks boxes as their 12 triangles,
// which are exact, and asks libccd's GJK where FCL's finds a cylinder free; the cpu and
// gpu backends check tessellations that contain the shape.
struct GjkCase {
  const char* name;
  const char* obstacle;         // the scene's obstacle
  Eigen::Vector3d v[3];         // the triangle, in the obstacle's frame (at the origin)
  Eigen::Vector3d barycentric;  // a point of the triangle inside the shape
  std::shared_ptr<fcl::CollisionGeometryd> shape;
  bool inside(const Eigen::Vector3d& p) const;
};

bool GjkCase::inside(const Eigen::Vector3d& p) const {
  if (shape->getNodeType() == fcl::GEOM_BOX) {
    const Eigen::Vector3d half = static_cast<const fcl::Boxd&>(*shape).side / 2;
    return (p.cwiseAbs() - half).maxCoeff() < 0;
  }
  const auto& c = static_cast<const fcl::Cylinderd&>(*shape);
  return p.head<2>().norm() < c.radius && std::abs(p.z()) < c.lz / 2;
}

std::vector<GjkCase> gjk_cases() {
  return {{"box",
           "box: [0.7, 0.7, 0.04]",
           {{-0.430465, -0.246655, -0.122517},
            {-0.300504, -0.413754, 0.054237},
            {-0.423918, -0.250770, -0.140854}},
           {0.14, 0.61, 0.25},
           std::make_shared<fcl::Boxd>(0.7, 0.7, 0.04)},
          {"cylinder",
           "cylinder: {radius: 0.1, length: 0.6}",
           {{-0.01380062614911208, -0.16412985602282176, 0.22021611606209729},
            {0.11276773423551927, -0.019761241204776001, 0.30884311209030313},
            {-0.031204191192993995, -0.18618702422817818, 0.24675108643798249}},
           {0.31, 0.69, 0},
           std::make_shared<fcl::Cylinderd>(0.1, 0.6)}};
}

Eigen::Vector3d point_inside(const GjkCase& c) {
  return c.barycentric.x() * c.v[0] + c.barycentric.y() * c.v[1] + c.barycentric.z() * c.v[2];
}

Scene gjk_case_scene(const GjkCase& c, testing::ScratchFolder* scratch) {
  std::ostringstream obj, yaml;
  obj.precision(17);
  for (const Eigen::Vector3d& v : c.v) obj << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  obj << "f 1 2 3\n";
  scratch->write("triangle.obj", obj.str());
  yaml << "name: gjk_" << c.name << "\nrobot: {mesh: triangle.obj}\nobstacles:\n  - " << c.obstacle
       << "\nbounds: {min: [-2, -2, -2], max: [2, 2, 2]}\n"
          "start: {base: {xyz: [-1.5, 0, 0], quat_wxyz: [1, 0, 0, 0]}}\n"
          "goal: {base: {xyz: [1.5, 0, 0], quat_wxyz: [1, 0, 0, 0]}}\n";
  return load_scene(scratch->write(std::string("gjk_") + c.name + ".yaml", yaml.str()));
}

TEST_F(FclCheckerTest, KnownAnswersWhereFclsGjkIsWrong) {
  const std::vector<float> identity = {0, 0, 0, 1, 0, 0, 0};
  for (const GjkCase& c : gjk_cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_TRUE(c.inside(point_inside(c))) << "the case's point is not inside the shape";
    // FCL's GJK on the bare pair: the premise of the case.
    auto triangle = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    triangle->beginModel();
    triangle->addTriangle(c.v[0], c.v[1], c.v[2]);
    triangle->endModel();
    fcl::CollisionObjectd a(triangle), b(c.shape);
    a.computeAABB();
    b.computeAABB();
    fcl::CollisionRequestd request;
    request.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd result;
    EXPECT_EQ(fcl::collide(&a, &b, request, result), 0u)
        << "FCL's GJK finds this contact now: the fcl backend's workaround (boxes as "
           "triangles, libccd's second opinion on cylinders) may no longer be needed";

    const Scene scene = gjk_case_scene(c, &scratch_);
    FclChecker fcl_checker(scene, 1);
    CpuChecker cpu(scene, 1);
    EXPECT_TRUE(fcl_checker.in_collision(identity.data()));
    EXPECT_TRUE(cpu.in_collision(identity.data()));
    double distance = -1;
    fcl_checker.distance(identity.data(), 1, &distance);
    EXPECT_EQ(distance, 0.0);
  }
}

// A box's verdicts from the fcl backend equal the separating-axis test in double on a
// triangle posed at random about the box (13 axes: the box's 3, the triangle's normal,
// and the 9 cross products of their edges), away from touching; the cpu backend never
// misses one and reports extra ones only within the band.
TEST_F(FclCheckerTest, BoxAgainstTriangleAsTheSeparatingAxisTestSays) {
  const GjkCase c = gjk_cases()[0];
  const Scene scene = gjk_case_scene(c, &scratch_);
  const Eigen::Vector3d half(0.35, 0.35, 0.02);
  // The signed depth: positive overlap along the axis of least overlap, or minus the
  // largest gap along a separating axis.
  const auto depth = [&](const Eigen::Vector3d v[3]) {
    const Eigen::Vector3d e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                         Eigen::Vector3d::UnitZ(), e[0].cross(e[1])};
    for (int i = 0; i < 3; ++i)
      for (const Eigen::Vector3d& edge : e) axes.push_back(Eigen::Vector3d::Unit(i).cross(edge));
    double overlap = std::numeric_limits<double>::infinity(), gap = 0;
    for (Eigen::Vector3d axis : axes) {
      if (axis.norm() < 1e-12) continue;
      axis.normalize();
      double lo = axis.dot(v[0]), hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = std::min(lo, axis.dot(v[k]));
        hi = std::max(hi, axis.dot(v[k]));
      }
      const double r = half.dot(axis.cwiseAbs());
      gap = std::max({gap, lo - r, -r - hi});
      overlap = std::min({overlap, r - lo, hi + r});
    }
    return gap > 0 ? -gap : overlap;
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const int n = 40000;
  std::vector<float> q(n * 7);
  for (int i = 0; i < n; ++i) {
    const Eigen::Quaterniond turn =
        Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized();
    // The triangle's centroid placed within 0.4, 0.4, 0.1 of the box's centre.
    const Eigen::Vector3d p = Eigen::Vector3d(0.4 * unit(rng), 0.4 * unit(rng), 0.1 * unit(rng)) -
                              turn * ((c.v[0] + c.v[1] + c.v[2]) / 3);
    const float row[7] = {float(p.x()),    float(p.y()),    float(p.z()),   float(turn.w()),
                          float(turn.x()), float(turn.y()), float(turn.z())};
    std::copy(row, row + 7, &q[i * 7]);
  }
  FclChecker fcl_checker(scene, 2);
  CpuChecker cpu(scene, 2);
  std::vector<std::uint8_t> by_fcl(n), by_cpu(n);
  fcl_checker.check(q.data(), n, by_fcl.data());
  cpu.check(q.data(), n, by_cpu.data());
  const double delta = tolerance_delta(scene);
  int hits = 0, compared = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Isometry3d X = scene.space.base_pose(&q[i * 7]);
    const Eigen::Vector3d v[3] = {X * c.v[0], X * c.v[1], X * c.v[2]};
    const double d = depth(v);
    if (std::abs(d) < 1e-9) continue;  // touching, within rounding
    ++compared;
    hits += d > 0;
    EXPECT_EQ(by_fcl[i], d > 0 ? 1 : 0) << "row " << i << ", depth " << d;
    if (d > 0) EXPECT_EQ(by_cpu[i], 1) << "row " << i << ", depth " << d;
    if (by_cpu[i] && d < 0) EXPECT_LT(-d, delta) << "row " << i;
  }
  EXPECT_GT(compared, n * 9 / 10);
  EXPECT_GT(hits, n / 10);
  EXPECT_LT(hits, compared - n / 10);
}

TEST(FclCheckerGpu, KnownAnswersWhereFclsGjkIsWrong) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  testing::ScratchFolder scratch;
  const std::vector<float> identity = {0, 0, 0, 1, 0, 0, 0};
  for (const GjkCase& c : gjk_cases()) {
    SCOPED_TRACE(c.name);
    const Scene scene = gjk_case_scene(c, &scratch);
    for (const Traversal traversal :
         {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced}) {
      GpuCheckerOptions options;
      options.traversal = traversal;
      options.host_calls_up_to = 0;  // on the GPU, not the host's core
      GpuChecker gpu(scene, options);
      std::uint8_t verdict = 0;
      gpu.check(identity.data(), 1, &verdict);
      EXPECT_EQ(verdict, 1) << traversal_name(traversal);
    }
  }
}

}  // namespace
}  // namespace gplanner
