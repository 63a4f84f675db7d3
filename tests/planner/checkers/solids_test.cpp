// Solids on every backend (docs/design.md, "Solids"), with answers known by
// construction: a link wholly inside a box, cylinder, sphere or closed mesh collides; an
// obstacle wholly inside a closed link collides; a link wholly inside another checked
// link collides; an open mesh stays a surface; `solid:` overrides; the drop of
// unreachable geometry keeps a solid that contains the robot; a gripper is planned around
// a thick table top, not through it. The cpu and fcl backends here, the gpu backend (each
// traversal) in the cases named Gpu, which skip where there is no device.

#include <gtest/gtest.h>

#include <sstream>

#include "gplanner/collision_gpu/cpu_batch_checker.h"
#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/checkers/gpu_checker.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplanner {
namespace {

// A closed axis-aligned box mesh centred at c, half sizes h, counter-clockwise outside,
// its vertices numbered from `first` (OBJ, 1-based). open_top leaves out the +z face.
std::string box_obj(Eigen::Vector3d c, Eigen::Vector3d h, int first = 1, bool open_top = false) {
  std::ostringstream obj;
  for (int i = 0; i < 8; ++i) {
    obj << "v " << c.x() + ((i & 1) ? h.x() : -h.x()) << " " << c.y() + ((i & 2) ? h.y() : -h.y())
        << " " << c.z() + ((i & 4) ? h.z() : -h.z()) << "\n";
  }
  const int faces[12][3] = {{1, 3, 4}, {1, 4, 2}, {1, 2, 6}, {1, 6, 5}, {3, 7, 8}, {3, 8, 4},
                            {1, 5, 7}, {1, 7, 3}, {2, 4, 8}, {2, 8, 6}, {5, 6, 8}, {5, 8, 7}};
  for (int f = 0; f < (open_top ? 10 : 12); ++f) {
    obj << "f " << faces[f][0] + first - 1 << " " << faces[f][1] + first - 1 << " "
        << faces[f][2] + first - 1 << "\n";
  }
  return obj.str();
}

std::string cube_obj(double half, bool open_top = false) {
  return box_obj(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(half), 1, open_top);
}

// A floating-base row: position and quaternion (w, x, y, z).
std::vector<float> at(double x, double y, double z, double w = 1, double qx = 0, double qy = 0,
                      double qz = 0) {
  return {float(x), float(y), float(z), float(w), float(qx), float(qy), float(qz)};
}

// A scene with answers known by construction: rows and their verdicts.
struct KnownAnswers {
  std::string name;
  Scene scene;
  std::vector<float> rows;  // shape [n, width]
  std::vector<std::uint8_t> expected;

  void add(const std::vector<float>& row, bool collides) {
    rows.insert(rows.end(), row.begin(), row.end());
    expected.push_back(collides ? 1 : 0);
  }
  std::size_t count() const { return expected.size(); }
};

std::vector<std::uint8_t> verdicts(CollisionChecker* checker, const KnownAnswers& k) {
  std::vector<std::uint8_t> v(k.count());
  checker->check(k.rows.data(), k.count(), v.data());
  return v;
}

// Every case, its files in `scratch`.
std::vector<KnownAnswers> known_answer_cases(const testing::ScratchFolder& scratch) {
  scratch.write("cube.obj", cube_obj(0.05));
  scratch.write("big_cube.obj", cube_obj(0.5));
  scratch.write("open_box.obj", cube_obj(0.5, true));
  scratch.write("small_open_box.obj", cube_obj(0.05, true));
  std::vector<KnownAnswers> cases;

  {  // A 10 cm cube robot wholly inside each kind of solid obstacle.
    KnownAnswers k{"link_inside_obstacles",
                   load_scene(scratch.write("inside.yaml", R"(
robot: {mesh: cube.obj}
obstacles:
  - {box: [1, 1, 1]}
  - {cylinder: {radius: 0.5, length: 1}, pose: {xyz: [3, 0, 0]}}
  - {sphere: 0.5, pose: {xyz: [6, 0, 0]}}
  - {mesh: big_cube.obj, pose: {xyz: [9, 0, 0]}}
bounds: {min: [-1, -2, -1], max: [10, 2, 1]}
start: {base: {xyz: [1.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [4.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
)")),
                   {},
                   {}};
    for (const double x : {0.0, 3.0, 6.0, 9.0}) {
      k.add(at(x, 0, 0), true);
      k.add(at(x + 0.2, -0.1, 0.25, 0.9, 0.1, 0.3, 0.2), true);  // off centre, turned
      k.add(at(x + 1.5, 0, 0), false);                           // between two
    }
    cases.push_back(std::move(k));
  }
  {  // Obstacles (primitive, closed mesh, open mesh) wholly inside a 1 m cube robot.
    KnownAnswers k{"obstacles_inside_link",
                   load_scene(scratch.write("holds.yaml", R"(
robot: {mesh: big_cube.obj}
obstacles:
  - {sphere: 0.05}
  - {box: [0.1, 0.1, 0.1], pose: {xyz: [3, 0, 0]}}
  - {mesh: cube.obj, pose: {xyz: [6, 0, 0]}}
  - {mesh: small_open_box.obj, pose: {xyz: [9, 0, 0]}}
bounds: {min: [-1, -2, -1], max: [10, 2, 1]}
start: {base: {xyz: [1.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [4.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
)")),
                   {},
                   {}};
    for (const double x : {0.0, 3.0, 6.0, 9.0}) {
      k.add(at(x, 0, 0), true);
      k.add(at(x + 0.2, 0.1, -0.1, 0.9, 0.1, 0.3, 0.2), true);
      k.add(at(x + 1.5, 0, 0), false);
    }
    cases.push_back(std::move(k));
  }
  // A link wholly inside another link of a checked pair, each way round: `inner` and
  // `outer` are the root and the grandchild (parent and child are never checked).
  for (const bool root_outside : {true, false}) {
    const std::string big = "<box size=\"0.4 0.4 0.4\"/>", small = "<box size=\"0.05 0.05 0.05\"/>";
    const std::string urdf = R"(<robot name="nested">
  <link name="root"><collision><geometry>)" +
                             (root_outside ? big : small) +
                             R"(</geometry></collision></link>
  <link name="slider"><collision><origin xyz="0 0 1"/><geometry>)" +
                             small + R"(</geometry></collision></link>
  <link name="tip"><collision><geometry>)" +
                             (root_outside ? small : big) +
                             R"(</geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="root"/><child link="slider"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="2" effort="1" velocity="1"/></joint>
  <joint name="mount" type="fixed"><parent link="slider"/><child link="tip"/></joint>
</robot>
)";
    const std::string name = root_outside ? "tip_inside_root" : "root_inside_tip";
    scratch.write(name + ".urdf", urdf);
    KnownAnswers k{name,
                   load_scene(scratch.write(name + ".yaml", "robot: {urdf: " + name +
                                                                R"(.urdf, planned_joints: [slide]}
start: {joints: {slide: 1.5}}
goal: {joints: {slide: 2}}
)")),
                   {},
                   {}};
    EXPECT_EQ(k.scene.robot.checked_pairs().size(), 1u);
    k.add({0.0f}, true);
    k.add({0.1f}, true);
    k.add({1.0f}, false);
    k.add({2.0f}, false);
    cases.push_back(std::move(k));
  }
  {  // An open box is a surface: a link inside it is free, one across its wall is not.
    KnownAnswers k{"open_mesh_is_a_surface",
                   load_scene(scratch.write("open.yaml", R"(
robot: {mesh: cube.obj}
obstacles:
  - {mesh: open_box.obj}
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {base: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0, 0, 0.8], quat_wxyz: [1, 0, 0, 0]}}
)")),
                   {},
                   {}};
    k.add(at(0, 0, 0), false);
    k.add(at(0.2, -0.3, 0.1, 0.9, 0.1, 0.3, 0.2), false);
    k.add(at(0.5, 0, 0), true);  // across the wall at x = 0.5
    k.add(at(0, 0, 0.8), false);
    cases.push_back(std::move(k));
  }
  {  // solid: false makes a closed mesh or a primitive a surface; solid: true on a
     // closed mesh is what it would be anyway.
    KnownAnswers k{"solid_overrides",
                   load_scene(scratch.write("overrides.yaml", R"(
robot: {mesh: cube.obj}
obstacles:
  - {box: [1, 1, 1], solid: false}
  - {mesh: big_cube.obj, pose: {xyz: [3, 0, 0]}, solid: false}
  - {mesh: big_cube.obj, pose: {xyz: [6, 0, 0]}, solid: true}
  - {sphere: 0.5, pose: {xyz: [9, 0, 0]}, solid: false}
bounds: {min: [-1, -2, -1], max: [10, 2, 1]}
start: {base: {xyz: [1.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [4.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
)")),
                   {},
                   {}};
    k.add(at(0, 0, 0), false);
    k.add(at(3, 0, 0), false);
    k.add(at(6, 0, 0), true);
    k.add(at(9, 0, 0), false);
    k.add(at(0.5, 0, 0), true);  // the surfaces are still there
    k.add(at(9.5, 0, 0), true);
    cases.push_back(std::move(k));
  }
  {  // A 4 m box around all the robot can reach: kept, not dropped as out of reach, and
     // every configuration collides.
    KnownAnswers k{"containing_solid_kept",
                   load_scene(scratch.write("boxed.yaml", R"(
robot: {mesh: cube.obj}
obstacles:
  - {box: [4, 4, 4]}
bounds: {min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5]}
start: {base: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0.3, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
)")),
                   {},
                   {}};
    const std::vector<float> q = testing::sample_configurations(k.scene, 500, 41);
    for (std::size_t i = 0; i < 500; ++i)
      k.add(std::vector<float>(q.begin() + 7 * i, q.begin() + 7 * (i + 1)), true);
    cases.push_back(std::move(k));
  }
  return cases;
}

TEST(Solids, KnownAnswersOnTheCpuAndFclBackends) {
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    CpuChecker cpu(k.scene);
    FclChecker fcl(k.scene);
    EXPECT_EQ(verdicts(&cpu, k), k.expected) << k.name << " (cpu)";
    EXPECT_EQ(verdicts(&fcl, k), k.expected) << k.name << " (fcl)";
  }
}

// The same answers without solids would be free: the core's containment step is what
// finds them (a surface test alone reports the robot inside the box free).
TEST(Solids, ContainmentIsWhatFindsThem) {
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    if (k.name != "link_inside_obstacles") continue;
    CollisionModel model = build_collision_model(k.scene);
    model.link_components.clear();
    model.environment_components.clear();
    CpuBatchChecker surfaces_only(model);
    std::vector<std::uint8_t> v(k.count());
    surfaces_only.check(k.rows.data(), k.count(), v.data());
    for (std::size_t i = 0; i < k.count(); ++i) EXPECT_EQ(v[i], 0) << "row " << i;
  }
}

TEST(Solids, OpenMeshesAreNamedInANotice) {
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    std::string notices;
    for (const std::string& n : k.scene.notices) notices += n + "\n";
    if (k.name == "open_mesh_is_a_surface") {
      EXPECT_NE(notices.find("open_box.obj: 1 of 1 connected component is open"), std::string::npos)
          << notices;
      EXPECT_NE(notices.find("surfaces"), std::string::npos) << notices;
    } else if (k.name == "obstacles_inside_link") {
      EXPECT_NE(notices.find("small_open_box.obj"), std::string::npos) << notices;
    } else {
      EXPECT_EQ(notices.find("open"), std::string::npos) << k.name << ": " << notices;
    }
  }
}

TEST(Solids, SolidTrueOnAnOpenMeshIsAnError) {
  testing::ScratchFolder scratch;
  scratch.write("cube.obj", cube_obj(0.05));
  scratch.write("open_box.obj", cube_obj(0.5, true));
  const std::string file = scratch.write("scene.yaml", R"(robot: {mesh: cube.obj}
obstacles:
  - {mesh: open_box.obj, solid: true}
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {base: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0, 0, 0.8], quat_wxyz: [1, 0, 0, 0]}}
)");
  try {
    load_scene(file);
    FAIL() << "solid: true on an open mesh loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.yaml:3: obstacles[0].solid"), std::string::npos) << what;
    EXPECT_NE(what.find("open_box.obj' is not closed"), std::string::npos) << what;
    EXPECT_NE(what.find("1 of 1 connected component is open (4 edges"), std::string::npos) << what;
  }
  const std::string bad = scratch.write("bad.yaml", R"(robot: {mesh: cube.obj}
obstacles:
  - {box: [1, 1, 1], solid: maybe}
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {base: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0, 0, 0.8], quat_wxyz: [1, 0, 0, 0]}}
)");
  try {
    load_scene(bad);
    FAIL() << "solid: maybe loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("obstacles[0].solid: expected true or false"),
              std::string::npos)
        << e.what();
  }
}

TEST(Solids, TheDropKeepsSolidsWholeAndSurfacesByTriangle) {
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    if (k.name != "containing_solid_kept") continue;
    ASSERT_EQ(k.scene.obstacles.size(), 1u);
    EXPECT_EQ(k.scene.obstacles[0].mesh_S.triangle_count(), 12u);
    EXPECT_EQ(k.scene.dropped_obstacle_triangles, 0u);
  }
  // As a surface, every triangle of the 4 m box lies out of reach.
  scratch.write("cube.obj", cube_obj(0.05));
  const Scene surface = load_scene(scratch.write("surface.yaml", R"(robot: {mesh: cube.obj}
obstacles:
  - {box: [4, 4, 4], solid: false}
bounds: {min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5]}
start: {base: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0.3, 0, 0], quat_wxyz: [1, 0, 0, 0]}}
)"));
  EXPECT_TRUE(surface.obstacles.empty());
  EXPECT_EQ(surface.dropped_obstacle_triangles, 12u);
}

// A rigid gripper (a palm and two fingers, three closed boxes) above a 0.3 m thick table
// top, its goal below it: the straight line goes through the table and is refused, its
// midpoint wholly inside the top; the planned path goes around, and FCL with the table
// as an FCL box finds every sample of it free.
TEST(Solids, AGripperIsPlannedAroundAThickTableTopNotThroughIt) {
  testing::ScratchFolder scratch;
  scratch.write("gripper.obj", box_obj({0, 0, 0.03}, {0.04, 0.01, 0.01}, 1) +
                                   box_obj({-0.03, 0, 0}, {0.01, 0.01, 0.03}, 9) +
                                   box_obj({0.03, 0, 0}, {0.01, 0.01, 0.03}, 17));
  const Scene scene = load_scene(scratch.write("table.yaml", R"(robot: {mesh: gripper.obj}
obstacles:
  - {name: table_top, box: [1.0, 1.0, 0.3], pose: {xyz: [0, 0, 0.6]}}
bounds: {min: [-1, -1, 0.05], max: [1, 1, 1.2]}
start: {base: {xyz: [0, 0, 0.9], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0, 0, 0.3], quat_wxyz: [1, 0, 0, 0]}}
planner: {seed: 3}
)"));
  ASSERT_EQ(scene.obstacles.size(), 1u);
  EXPECT_TRUE(scene.obstacles[0].is_solid_primitive());
  CpuChecker cpu(scene);
  FclChecker fcl(scene);
  for (CollisionChecker* checker :
       {static_cast<CollisionChecker*>(&cpu), static_cast<CollisionChecker*>(&fcl)}) {
    EXPECT_FALSE(checker->in_collision(scene.start.data())) << checker->backend();
    EXPECT_FALSE(checker->in_collision(scene.goal.data())) << checker->backend();
    // Only the midpoint, wholly inside the table top, is checked.
    EXPECT_NEAR(first_collision_on_straight_line(scene, checker, 0.5), 0.5, 1e-9)
        << checker->backend();
    EXPECT_GT(first_collision_on_straight_line(scene, checker), 0) << checker->backend();
  }
  auto neighbors = make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu");
  PlanOptions options = plan_options(scene);
  options.time_limit_s = 120;
  RoadmapPlanner planner(scene, &cpu, neighbors.get(), RoadmapStrategy::kLazyPrm, options);
  const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(scene, result.path), "");
  // Around the table: some waypoint lies beside it (|x| or |y| beyond its half width).
  bool beside = false;
  for (std::size_t i = 0; i < result.path.size(); i += scene.space.width())
    beside = beside || std::abs(result.path[i]) > 0.5f || std::abs(result.path[i + 1]) > 0.5f;
  EXPECT_TRUE(beside);
}

// Solid spheres and cylinders are tessellated so that their faces lie within a quarter
// of the band of the exact shape (which the fcl backend checks); a sphere too large for
// its triangle budget gets an allowance and a notice, and the comparison with FCL
// counts collisions within it as within the band.
TEST(Solids, PrimitivesAreTessellatedWithinTheBandOrGetAnAllowance) {
  testing::ScratchFolder scratch;
  scratch.write("cube.obj", cube_obj(0.05));
  const Scene scene = load_scene(scratch.write("primitives.yaml", R"(robot: {mesh: cube.obj}
obstacles:
  - {name: post, cylinder: {radius: 0.5, length: 1}}
  - {name: ball, sphere: 0.05, pose: {xyz: [3, 0, 0]}}
  - {name: globe, sphere: 2, pose: {xyz: [8, 0, 0]}}
bounds: {min: [-1, -3, -3], max: [11, 3, 3]}
start: {base: {xyz: [1.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [4.5, 1.5, 0], quat_wxyz: [1, 0, 0, 0]}}
)"));
  const double delta = tolerance_delta(scene);
  ASSERT_EQ(scene.obstacles.size(), 3u);
  const auto excess = [](const Obstacle& o) {
    double most = 0;
    for (const Eigen::Vector3d& p_S : o.mesh_S.vertices) {
      const Eigen::Vector3d p = o.X_SO.inverse() * p_S;
      const double r = o.shape == ObstacleShape::kSphere ? p.norm() : p.head<2>().norm();
      if (o.shape == ObstacleShape::kSphere || r > 1e-9)
        most = std::max(most, r - o.dimensions.x());
    }
    return most;
  };
  for (int i : {0, 1}) {
    EXPECT_TRUE(scene.obstacles[i].is_solid_primitive());
    EXPECT_EQ(scene.obstacles[i].allowance_m, 0.0) << scene.obstacles[i].name;
    EXPECT_LE(excess(scene.obstacles[i]), delta / 4) << scene.obstacles[i].name;
    EXPECT_GE(excess(scene.obstacles[i]), 0.0) << scene.obstacles[i].name;
  }
  const Obstacle& globe = scene.obstacles[2];
  EXPECT_GT(globe.allowance_m, delta / 4);
  EXPECT_NEAR(globe.allowance_m, excess(globe), 1e-12);
  std::string notices;
  for (const std::string& n : scene.notices) notices += n + "\n";
  EXPECT_NE(notices.find("obstacle 'globe'"), std::string::npos) << notices;
  EXPECT_NE(notices.find("sphere's tessellation lies up to"), std::string::npos) << notices;
  // The cube beside each, its face (at x, facing a tessellation vertex) some way from
  // the exact shape: never a missed collision, never an extra one outside the band (and
  // the globe's allowance). Within the globe's allowance the cpu backend reports a
  // collision that FCL's exact sphere does not, which only the allowance excuses.
  std::vector<float> rows;
  std::vector<int> expect_cpu;  // 1, 0, or -1: either, within the band
  const auto beside = [&](double surface_x, double gap, int cpu_verdict) {
    const std::vector<float> row = at(surface_x + 0.05 + gap, 0, 0);
    rows.insert(rows.end(), row.begin(), row.end());
    expect_cpu.push_back(cpu_verdict);
  };
  for (const double surface_x : {0.5, 3.05}) {
    beside(surface_x, 0.3 * delta, -1);
    beside(surface_x, 1.5 * delta, 0);
  }
  ASSERT_GT(globe.allowance_m, delta);
  beside(10, delta / 2 + 0.5 * globe.allowance_m, 1);
  beside(10, delta + 2 * globe.allowance_m, 0);
  const std::size_t n = rows.size() / 7;
  CpuChecker cpu(scene);
  FclChecker fcl(scene);
  std::vector<std::uint8_t> a(n), b(n);
  cpu.check(rows.data(), n, a.data());
  fcl.check(rows.data(), n, b.data());
  const CheckerComparison c = compare_verdicts(rows.data(), n, 7, a.data(), b.data(), &fcl, delta);
  EXPECT_EQ(c.missed_collisions, 0u);
  EXPECT_EQ(c.extra_outside_band, 0u);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(b[i], 0) << "row " << i;
    if (expect_cpu[i] >= 0) EXPECT_EQ(a[i], expect_cpu[i]) << "row " << i;
  }
}

// Every traversal, and the balanced traversal's small-batch kernel, gives the known
// answers and the cpu backend's verdicts.
TEST(SolidsGpu, KnownAnswersOnEveryTraversal) {
  REQUIRE_GPU();
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    CpuChecker cpu(k.scene);
    const std::vector<std::uint8_t> on_cpu = verdicts(&cpu, k);
    EXPECT_EQ(on_cpu, k.expected) << k.name;
    for (const Traversal t : {Traversal::kBasic, Traversal::kPacket, Traversal::kBalanced}) {
      for (const bool small : {false, true}) {
        if (small && t != Traversal::kBalanced) continue;
        GpuCheckerOptions options;
        options.traversal = t;
        options.warp_per_pair_up_to = small ? k.count() : 0;
        options.host_calls_up_to = 0;
        GpuChecker gpu(k.scene, options);
        const std::vector<std::uint8_t> on_gpu = verdicts(&gpu, k);
        const std::string what = k.name + " " + traversal_name(t) + (small ? " small batch" : "");
        EXPECT_GT(gpu.last_stats().milliseconds, 0.0) << what << ": the GPU did not run";
        EXPECT_EQ(gpu.last_stats().warp_per_pair, small) << what;
        EXPECT_EQ(on_gpu, on_cpu) << what;
      }
    }
  }
}

// The balanced traversal queues each point its containment walk finds in a solid's box
// and runs the point's three rays a thread each; points beyond the queue's capacity
// (1,024 under a 1 MB memory cap) are tested where they are found. Every case's rows,
// repeated to 3,072 rows (a one-kernel batch of 1,024; and chunks of up to 2,330, the
// first in rounds): in obstacles_inside_link two rows in three hold an obstacle, so a
// chunk queues more than 1,024 points. The verdicts stay the cpu backend's, row by row.
TEST(SolidsGpu, QueuedPointsInSolidsAndThoseBeyondTheQueueKeepTheirAnswers) {
  REQUIRE_GPU();
  testing::ScratchFolder scratch;
  for (KnownAnswers& k : known_answer_cases(scratch)) {
    KnownAnswers many{k.name, k.scene, {}, {}};
    while (many.count() < 3072) {
      many.rows.insert(many.rows.end(), k.rows.begin(), k.rows.end());
      many.expected.insert(many.expected.end(), k.expected.begin(), k.expected.end());
    }
    for (const std::size_t rows : {std::size_t(1024), many.count()}) {
      KnownAnswers part{k.name, k.scene, {}, {}};
      const int width = k.scene.space.width();
      part.rows.assign(many.rows.begin(), many.rows.begin() + rows * width);
      part.expected.assign(many.expected.begin(), many.expected.begin() + rows);
      CpuChecker cpu(part.scene);
      const std::vector<std::uint8_t> on_cpu = verdicts(&cpu, part);
      EXPECT_EQ(on_cpu, part.expected) << k.name;
      GpuCheckerOptions options;
      options.traversal = Traversal::kBalanced;
      options.memory_cap_bytes = std::size_t(1) << 20;
      options.warp_per_pair_up_to = 1024;
      options.host_calls_up_to = 0;
      GpuChecker gpu(part.scene, options);
      const std::vector<std::uint8_t> on_gpu = verdicts(&gpu, part);
      const std::string what = k.name + ", " + std::to_string(rows) + " rows";
      if (rows <= 1024)
        EXPECT_TRUE(gpu.last_stats().warp_per_pair) << what << ": not one kernel";
      else
        EXPECT_GT(gpu.last_stats().rounds, 0u) << what << ": no chunk ran in rounds";
      EXPECT_EQ(on_gpu, on_cpu) << what;
    }
  }
}

}  // namespace
}  // namespace gplanner
