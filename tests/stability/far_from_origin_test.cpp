// Stability: scenes far from the world origin (1e3 to 1e5 m). There a float cannot
// place a pose within the tolerance band (its spacing at 1e5 m is 7.8 mm); the scene
// frame (Scene::p_WS) makes everything the float core sees relative to a point near
// the scene, in double, first. The contacts of known distance keep the band there on
// every backend and for every kind of base, a small scene is planned at 1e5 m and its
// path file gives world poses to within double rounding, and the same cases without
// the frame break the band (so these tests are not vacuous).

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "contact_cases.h"
#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/output/path_file.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"

namespace gplanner {
namespace {

using testing::Contact;
using testing::ScratchFolder;

const std::vector<double> kSides = {1e-2, 1.0, 1e2};
const double kDistances[] = {1e3, 1e4, 1e5};

// A point `distance` from the origin, off every axis and off any round number.
Eigen::Vector3d far_point(double distance) {
  return distance * Eigen::Vector3d(1, -0.6, 0.3).normalized() + Eigen::Vector3d(0.37, -0.13, 0.09);
}

Scene load_contact_scene(const ScratchFolder& scratch, double side, Contact contact,
                         const Eigen::Vector3d& p_WO) {
  scratch.write("cube.obj", testing::robot_obj(side, contact));
  return load_scene(scratch.write("scene.yaml", testing::contact_scene_yaml(side, contact, p_WO)));
}

// The largest error float rounding makes in a coordinate of magnitude x: half its
// spacing there.
double float_rounding(double x) {
  const float f = static_cast<float>(x);
  return 0.5 * (std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
}

TEST(StabilityFarFromOrigin, ShippedScenesKeepTheWorldFrame) {
  // Their rows, roadmaps and results stay as they were.
  for (const auto& entry :
       std::filesystem::directory_iterator(testing::project_root() + "/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    const Scene scene = load_scene(entry.path().string());
    EXPECT_TRUE(scene.p_WS.isZero()) << entry.path();
    EXPECT_TRUE(scene.space.row_origin.isZero()) << entry.path();
  }
}

TEST(StabilityFarFromOrigin, TheFrameFollowsTheScene) {
  EXPECT_TRUE(
      scene_frame_origin(Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(3, 3, 3)))
          .isZero());
  // Centre (1e5 + 0.37, ...), diagonal 8 sqrt(3) = 13.9: rounded to tens.
  const Eigen::Vector3d c(1e5 + 0.37, -2e4 - 6.2, 36.4);
  const Eigen::AlignedBox3d box(c.array() - 4, c.array() + 4);
  EXPECT_EQ(scene_frame_origin(box), Eigen::Vector3d(1e5, -2e4 - 10, 40));

  ScratchFolder scratch;
  const Eigen::Vector3d p_WO = far_point(1e5);
  const Scene scene = load_contact_scene(scratch, 1.0, Contact::kFaceFace, p_WO);
  ASSERT_FALSE(scene.p_WS.isZero());
  EXPECT_EQ(scene.space.row_origin, scene.p_WS);
  EXPECT_LT((scene.p_WS - p_WO).norm(), 10.0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(std::fmod(scene.p_WS[k], 10.0), 0.0);
  EXPECT_LT(scene.bounds_S().center().norm(), 10.0);
  // The start row is the world start less p_WS, in double, then rounded.
  for (int k = 0; k < 3; ++k) {
    const double world = p_WO[k] + (k == 0 ? -3.0 : 0.0);
    EXPECT_EQ(scene.start[k], static_cast<float>(world - scene.p_WS[k]));
  }
  // The notice says so, once.
  ASSERT_EQ(scene.notices.size(), 1u);
  EXPECT_NE(scene.notices[0].find("relative to the world point"), std::string::npos);
}

TEST(StabilityFarFromOrigin, ContactsKeepTheBandCpuAndFcl) {
  for (const double distance : kDistances) {
    SCOPED_TRACE("obstacle " + std::to_string(distance) + " m from the origin");
    testing::expect_contacts_within_band({"cpu", "fcl"}, kSides, far_point(distance));
  }
}

TEST(StabilityFarFromOrigin, GpuKeepsTheBand) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  for (const double distance : kDistances) {
    SCOPED_TRACE("obstacle " + std::to_string(distance) + " m from the origin");
    testing::expect_contacts_within_band({"gpu"}, kSides, far_point(distance));
  }
}

// The same contacts at 1e5 m as the loader placed scenes before the scene frame: the
// world's coordinates, rows rounded to float there. Float spacing exceeds the band, and
// the cpu backend breaks it.
TEST(StabilityFarFromOrigin, WithoutTheFrameFloatBreaksTheBand) {
  const double side = 1.0;
  const Eigen::Vector3d p_WO = far_point(1e5);
  std::size_t worst_rounding_cases = 0;
  std::size_t broken[2] = {0, 0};
  const char* backends[2] = {"cpu", "fcl"};
  double delta = 0;
  for (const Contact contact : testing::kAllContacts) {
    ScratchFolder scratch;
    Scene scene = load_contact_scene(scratch, side, contact, Eigen::Vector3d::Zero());
    ASSERT_TRUE(scene.p_WS.isZero());
    for (Obstacle& obstacle : scene.obstacles) {
      for (Eigen::Vector3d& p : obstacle.mesh_S.vertices) p += p_WO;
    }
    scene.space.base_min += p_WO;
    scene.space.base_max += p_WO;
    delta = tolerance_delta(scene);
    for (int b = 0; b < 2; ++b) {
      std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backends[b]);
      for (const double gap : testing::contact_gaps(side, delta)) {
        const std::vector<double> pose = testing::contact_pose(side, contact, gap, p_WO);
        std::vector<float> q(pose.begin(), pose.end());
        if (b == 0 && std::abs(q[0] - pose[0]) > delta) ++worst_rounding_cases;
        const bool hit = checker->in_collision(q.data());
        broken[b] += (gap < 0 && !hit) || (gap > delta && hit);
      }
    }
  }
  std::cout << "without the scene frame at 1e5 m: " << broken[0] << " cpu and " << broken[1]
            << " fcl verdicts outside the band; " << worst_rounding_cases
            << " poses moved by more than delta\n";
  EXPECT_GT(float_rounding(p_WO.x()), 10 * delta);
  EXPECT_GT(worst_rounding_cases, 0u);
  EXPECT_GT(broken[0], 0u);
}

// A robot of two links (a base block and an arm sliding along x, x in [s, s + 1] in the
// root's frame) and an obstacle whose near face lies 2 m along x from the root: the gap
// is 1 - s. Fixed, planar and floating bases, the root 1e5 m from the origin.
std::string slider_urdf() {
  return "<robot name=\"slider\">\n"
         "<link name=\"base\"><collision><geometry><box size=\"0.2 0.2 0.2\"/></geometry>"
         "</collision></link>\n"
         "<link name=\"arm\"><collision><origin xyz=\"0.5 0 0\"/><geometry>"
         "<box size=\"1 0.1 0.1\"/></geometry></collision></link>\n"
         "<joint name=\"slide\" type=\"prismatic\"><parent link=\"base\"/><child link=\"arm\"/>"
         "<axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"1.5\" effort=\"1\" velocity=\"1\"/>"
         "</joint>\n</robot>\n";
}

std::string slider_scene_yaml(const std::string& base, const Eigen::Vector3d& p_WR) {
  std::ostringstream out;
  out << std::setprecision(17) << "name: slider\nrobot:\n  urdf: slider.urdf\n  base: " << base
      << "\n  planned_joints: [slide]\n";
  if (base == "fixed")
    out << "  base_pose: {xyz: [" << p_WR.x() << ", " << p_WR.y() << ", " << p_WR.z() << "]}\n";
  out << "obstacles:\n  - box: [0.5, 0.5, 0.5]\n    pose: {xyz: [" << p_WR.x() + 2.25 << ", "
      << p_WR.y() << ", " << p_WR.z() << "]}\n";
  std::string start_base, goal_base;
  if (base == "planar") {
    out << "bounds: {min: [" << p_WR.x() - 3 << ", " << p_WR.y() - 3 << "], max: [" << p_WR.x() + 3
        << ", " << p_WR.y() + 3 << "]}\n";
    std::ostringstream b;
    b << std::setprecision(17) << "base: {xy: [" << p_WR.x() << ", " << p_WR.y()
      << "], theta: 0}, ";
    start_base = goal_base = b.str();
  } else if (base == "floating") {
    out << "bounds: {min: [" << p_WR.x() - 3 << ", " << p_WR.y() - 3 << ", " << p_WR.z() - 3
        << "], max: [" << p_WR.x() + 3 << ", " << p_WR.y() + 3 << ", " << p_WR.z() + 3 << "]}\n";
    std::ostringstream b;
    b << std::setprecision(17) << "base: {xyz: [" << p_WR.x() << ", " << p_WR.y() << ", "
      << p_WR.z() << "], quat_wxyz: [1, 0, 0, 0]}, ";
    start_base = goal_base = b.str();
  }
  out << "start: {" << start_base << "joints: {slide: 0}}\n"
      << "goal: {" << goal_base << "joints: {slide: 0.5}}\n";
  return out.str();
}

TEST(StabilityFarFromOrigin, FixedPlanarAndFloatingBasesKeepTheBand) {
  Eigen::Vector3d p_WR = far_point(1e5);
  for (const std::string base : {"fixed", "planar", "floating"}) {
    if (base == "planar") p_WR.z() = 0;  // the plane is the world's xy plane
    ScratchFolder scratch;
    scratch.write("slider.urdf", slider_urdf());
    const Scene scene = load_scene(scratch.write("scene.yaml", slider_scene_yaml(base, p_WR)));
    ASSERT_FALSE(scene.p_WS.isZero()) << base;
    const double delta = tolerance_delta(scene);
    const int w = scene.space.width();
    std::vector<double> values(w, 0.0);
    if (base == "planar") {
      values[0] = p_WR.x();
      values[1] = p_WR.y();
    } else if (base == "floating") {
      for (int k = 0; k < 3; ++k) values[k] = p_WR[k];
      values[3] = 1;
    }
    // The root where the file put it: the world pose the rows stand for.
    std::vector<float> q(w);
    scene.space.from_file_values(values.data(), q.data());
    const Eigen::Vector3d p_WR_rows =
        (scene.X_WS() * scene.space.base_pose(q.data())).translation();
    EXPECT_LT((p_WR_rows - p_WR).norm(), 1e-2 * delta) << base;
    for (const char* backend : {"cpu", "fcl"}) {
      std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
      for (const double gap : testing::contact_gaps(1.0, delta)) {
        values[w - 1] = 1 - gap;
        scene.space.from_file_values(values.data(), q.data());
        const bool hit = checker->in_collision(q.data());
        const std::string what = std::string(backend) + ", " + base + " base, gap " +
                                 std::to_string(gap / delta) + " delta";
        if (gap < 0) EXPECT_TRUE(hit) << what << ": a penetration reported free";
        if (gap > delta) EXPECT_FALSE(hit) << what << ": a collision outside the band";
      }
    }
  }
}

// A cube of 0.4 m from one side of a 1 m block to the other, 1e5 m from the origin.
std::string block_scene_yaml(const Eigen::Vector3d& p_WC, double start_x) {
  std::ostringstream out;
  out << std::setprecision(17) << "name: far block\nrobot:\n  mesh: cube.obj\nobstacles:\n"
      << "  - box: [1, 1, 1]\n    pose: {xyz: [" << p_WC.x() << ", " << p_WC.y() << ", " << p_WC.z()
      << "]}\n"
      << "bounds: {min: [" << p_WC.x() - 2 << ", " << p_WC.y() - 2 << ", " << p_WC.z() - 2
      << "], max: [" << p_WC.x() + 2 << ", " << p_WC.y() + 2 << ", " << p_WC.z() + 2 << "]}\n"
      << "start:\n  base: {xyz: [" << start_x << ", " << p_WC.y() << ", " << p_WC.z()
      << "], quat_wxyz: [1, 0, 0, 0]}\n"
      << "goal:\n  base: {xyz: [" << p_WC.x() + 1.5 << ", " << p_WC.y() << ", " << p_WC.z()
      << "], quat_wxyz: [0.70710678118654757, 0, 0, 0.70710678118654757]}\n"
      << "planner: {seed: 3, time_limit_s: 60, roadmap: {milestones: 300}}\n";
  return out.str();
}

// The base position of waypoint `index` (0 first, -1 last) of a path file.
Eigen::Vector3d path_file_position(const std::string& file, int index) {
  std::ifstream in(file);
  std::vector<Eigen::Vector3d> positions;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t at = line.find("base: {position: [");
    if (at == std::string::npos) continue;
    Eigen::Vector3d p;
    if (std::sscanf(line.c_str() + at, "base: {position: [%lf, %lf, %lf]", &p.x(), &p.y(),
                    &p.z()) == 3)
      positions.push_back(p);
  }
  if (positions.empty()) return Eigen::Vector3d::Constant(NAN);
  return index < 0 ? positions.back() : positions[index];
}

void expect_plans_far_from_origin(const std::string& backend) {
  ScratchFolder scratch;
  scratch.write("cube.obj", testing::cube_obj(0.4));
  const Eigen::Vector3d p_WC = far_point(1e5);
  const Scene scene =
      load_scene(scratch.write("scene.yaml", block_scene_yaml(p_WC, p_WC.x() - 1.5)));
  ASSERT_FALSE(scene.p_WS.isZero());
  std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
  ASSERT_EQ(checker->backend(), backend);
  check_start_and_goal(scene, checker.get());
  EXPECT_GE(first_collision_on_straight_line(scene, checker.get()), 0) << "a real problem";
  const ConfigurationMetric metric = make_metric(scene.space, scene.planner);
  std::unique_ptr<NeighborFinder> neighbors = make_neighbor_finder(metric, backend);
  RoadmapPlanner planner(scene, checker.get(), neighbors.get(), RoadmapStrategy::kLazyPrm,
                         plan_options(scene));
  const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;

  // Every segment free under FCL at 200 samples.
  const int w = scene.space.width();
  const std::size_t m = result.path.size() / w;
  std::vector<float> samples;
  std::vector<float> q(w);
  for (std::size_t i = 0; i + 1 < m; ++i) {
    for (int s = 0; s <= 200; ++s) {
      scene.space.interpolate(&result.path[i * w], &result.path[(i + 1) * w], s / 200.0, q.data());
      samples.insert(samples.end(), q.begin(), q.end());
    }
  }
  FclChecker fcl(scene);
  std::vector<std::uint8_t> verdicts(samples.size() / w);
  fcl.check(samples.data(), verdicts.size(), verdicts.data());
  std::size_t hits = 0;
  for (const std::uint8_t v : verdicts) hits += v;
  EXPECT_EQ(hits, 0u) << "of " << verdicts.size() << " samples of the path";

  // The path file gives the world poses, to within double rounding: not the float
  // row's millimetres.
  const std::string file = scratch.path() + "/path.yaml";
  write_path_file(file, scene, result, "lazyprm", checker->backend());
  const Eigen::Vector3d start_W(p_WC.x() - 1.5, p_WC.y(), p_WC.z());
  const Eigen::Vector3d goal_W(p_WC.x() + 1.5, p_WC.y(), p_WC.z());
  EXPECT_LT((path_file_position(file, 0) - start_W).norm(), 1e-6);
  EXPECT_LT((path_file_position(file, -1) - goal_W).norm(), 1e-6);
  std::cout << "planned at 1e5 m on " << backend << ": " << m << " waypoints in "
            << result.times.total << " s; float alone would round the start by up to "
            << float_rounding(start_W.x()) << " m\n";
}

TEST(StabilityFarFromOrigin, PlansASmallSceneCpu) { expect_plans_far_from_origin("cpu"); }

TEST(StabilityFarFromOrigin, GpuPlansASmallScene) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_plans_far_from_origin("gpu");
}

TEST(StabilityFarFromOrigin, GplanCheckWritesWorldRows) {
  ScratchFolder scratch;
  scratch.write("cube.obj", testing::cube_obj(0.4));
  const Eigen::Vector3d p_WC = far_point(1e5);
  const std::string scene = scratch.write("scene.yaml", block_scene_yaml(p_WC, p_WC.x() - 1.5));
  const std::string rows = scratch.path() + "/rows.txt";
  const testing::CommandResult run =
      testing::run_gplan("check '" + scene + "' --n 50 --backend cpu --out '" + rows + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("relative to the world point"), std::string::npos) << run.output;
  std::ifstream in(rows);
  std::string line;
  std::size_t lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    std::istringstream values(line);
    double x, y, z;
    values >> x >> y >> z;
    EXPECT_LE(std::abs(x - p_WC.x()), 2) << line;
    EXPECT_LE(std::abs(y - p_WC.y()), 2) << line;
    EXPECT_LE(std::abs(z - p_WC.z()), 2) << line;
  }
  EXPECT_EQ(lines, 50u);
}

TEST(StabilityFarFromOrigin, BadInputIsReportedInWorldCoordinates) {
  ScratchFolder scratch;
  scratch.write("cube.obj", testing::cube_obj(0.4));
  const Eigen::Vector3d p_WC(100000.25, 2000, 30);
  const std::string scene = scratch.write("scene.yaml", block_scene_yaml(p_WC, 100007.75));
  try {
    load_scene(scene);
    FAIL() << "a start outside the bounds was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("start"), std::string::npos) << what;
    EXPECT_NE(what.find("x = 100007.75 is outside the bounds [99998.25, 100002.25]"),
              std::string::npos)
        << what;
  }
}

}  // namespace
}  // namespace gplanner
