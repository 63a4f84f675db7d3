// The real PR2 and Talos descriptions from ../shared/data load and answer a batch.

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/urdf_loader.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;

struct RealRobot {
  std::string urdf, srdf;
  PackageMap packages;
};

// Skips the calling test when the shared data is not there.
#define REQUIRE_SHARED_DATA(data)                  \
  const std::string data = testing::shared_data(); \
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)"

RealRobot pr2(const std::string& data) {
  return {data + "/moveit_resources_pr2_description/urdf/robot.xml",
          data + "/pr2_moveit_config/config/pr2.srdf",
          {{"moveit_resources_pr2_description", data + "/moveit_resources_pr2_description"}}};
}

RealRobot talos(const std::string& data) {
  const std::string root = data + "/example-robot-data/robots/talos_data";
  return {root + "/robots/talos_reduced.urdf",
          root + "/srdf/talos.srdf",
          {{"example-robot-data", data + "/example-robot-data"}}};
}

int single_dof_joints(const RobotModel& robot) {
  int count = 0;
  for (const Joint& joint : robot.joints) count += joint.is_single_dof() && joint.mimic_joint < 0;
  return count;
}

TEST(RealRobots, Pr2Loads) {
  REQUIRE_SHARED_DATA(data);
  const RealRobot files = pr2(data);
  RobotModel robot = load_urdf(files.urdf, files.packages, {"test", 0, "urdf"});
  std::vector<std::string> notices;
  const int read = apply_srdf(&robot, files.srdf, {"test", 0, "srdf"}, &notices);
  EXPECT_EQ(robot.links.size(), 95u);
  EXPECT_EQ(robot.joints.size(), 94u);
  EXPECT_EQ(read, 1081);
  // Mimic joints (the gripper fingers) follow their masters.
  int mimics = 0;
  for (const Joint& joint : robot.joints) mimics += joint.mimic_joint >= 0;
  EXPECT_GT(mimics, 0);
  EXPECT_EQ(robot.joints[robot.find_joint("r_forearm_roll_joint")].type, JointType::kContinuous);
  // 37 STL meshes plus 17 URDF primitives, about 30k triangles in all.
  EXPECT_GT(robot.triangle_count(), 20000u);
  EXPECT_LT(robot.triangle_count(), 60000u);
  EXPECT_GT(robot.checked_pairs().size(), 100u);
  std::cout << "PR2: " << robot.links.size() << " links, " << robot.joints.size() << " joints ("
            << single_dof_joints(robot) << " with a value), " << robot.triangle_count()
            << " triangles, " << robot.disabled_pairs.size() << " disabled pairs, "
            << robot.checked_pairs().size() << " checked\n";
}

TEST(RealRobots, TalosLoadsWithItsQuirks) {
  REQUIRE_SHARED_DATA(data);
  const RealRobot files = talos(data);
  RobotModel robot = load_urdf(files.urdf, files.packages, {"test", 0, "urdf"});
  std::vector<std::string> notices;
  const int read = apply_srdf(&robot, files.srdf, {"test", 0, "srdf"}, &notices);
  EXPECT_EQ(single_dof_joints(robot), 32);
  EXPECT_EQ(read, 459);
  // rotor_params, specificities and gripper are outside the SRDF core: one notice each.
  EXPECT_GE(notices.size(), 2u);
  for (const std::string& notice : notices) EXPECT_NE(notice.find("talos.srdf"), std::string::npos);
  EXPECT_GT(robot.triangle_count(), 10000u);
  std::cout << "Talos: " << robot.links.size() << " links, " << robot.joints.size() << " joints, "
            << robot.triangle_count() << " triangles, " << robot.disabled_pairs.size()
            << " disabled pairs, " << robot.checked_pairs().size() << " checked\n";
}

using NamePair = std::pair<std::string, std::string>;

NamePair named(const RobotModel& robot, int a, int b) {
  return std::minmax(robot.links[a].name, robot.links[b].name);
}

// The SRDF's disable_collisions pairs giving `reason` (MoveIt Setup Assistant's
// "Adjacent", "Default", "Never", ...), both links carrying geometry in `robot`.
std::set<NamePair> srdf_pairs(const std::string& srdf, const std::string& reason,
                              const RobotModel& robot) {
  const std::string xml = testing::read_file(srdf);
  const std::regex pair("<disable_collisions link1=\"([^\"]+)\" link2=\"([^\"]+)\" reason=\"" +
                        reason + "\"");
  std::set<NamePair> pairs;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), pair); it != std::sregex_iterator();
       ++it) {
    const int a = robot.find_link((*it)[1]), b = robot.find_link((*it)[2]);
    if (a < 0 || b < 0 || robot.links[a].collision.empty() || robot.links[b].collision.empty())
      continue;
    pairs.insert(named(robot, a, b));
  }
  return pairs;
}

std::set<NamePair> adjacent_with_geometry(const RobotModel& robot) {
  std::set<NamePair> pairs;
  for (const auto& [a, b] : adjacent_link_pairs(robot)) {
    if (!robot.links[a].collision.empty() && !robot.links[b].collision.empty())
      pairs.insert(named(robot, a, b));
  }
  return pairs;
}

// The checked pairs that FCL finds colliding with every joint at 0 (or the nearest
// limit) and mimic joints following: MoveIt's default pose, which its Setup Assistant
// checks for "Default" pairs.
std::set<NamePair> colliding_at_default_pose(const RobotModel& robot) {
  std::vector<double> positions(robot.joints.size(), 0.0);
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const Joint& joint = robot.joints[j];
    if (joint.is_single_dof()) positions[j] = std::min(std::max(0.0, joint.lower), joint.upper);
  }
  for (std::size_t j = 0; j < robot.joints.size(); ++j) {
    const Joint& joint = robot.joints[j];
    if (joint.mimic_joint >= 0)
      positions[j] = joint.mimic_multiplier * positions[joint.mimic_joint] + joint.mimic_offset;
  }
  std::vector<Eigen::Isometry3d> X_WL;
  forward_kinematics(robot, Eigen::Isometry3d::Identity(), positions.data(), &X_WL);
  std::vector<std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>>> models(robot.links.size());
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    const TriangleMesh& mesh = robot.links[l].collision;
    if (mesh.empty()) continue;
    models[l] = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
    models[l]->beginModel();
    for (const Eigen::Vector3i& t : mesh.triangles)
      models[l]->addTriangle(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    models[l]->endModel();
  }
  std::set<NamePair> colliding;
  for (const auto& [a, b] : robot.checked_pairs()) {
    const fcl::CollisionObjectd object_a(models[a], X_WL[a]), object_b(models[b], X_WL[b]);
    fcl::CollisionResultd result;
    if (fcl::collide(&object_a, &object_b, fcl::CollisionRequestd(), result) > 0)
      colliding.insert(named(robot, a, b));
  }
  return colliding;
}

// Without its SRDF, a real robot's adjacent links are those MoveIt's Setup Assistant
// wrote into the SRDF as "Adjacent" (pairs of links with collision geometry), and none
// of the pairs colliding at the default pose is one of them: the robot does not report
// its own joints as collisions. Returns the colliding pairs.
std::set<NamePair> adjacency_is_moveits(const RealRobot& files, const std::string& robot_name) {
  const RobotModel robot = load_urdf(files.urdf, files.packages, {"test", 0, "urdf"});
  const std::set<NamePair> adjacent = adjacent_with_geometry(robot);
  const std::set<NamePair> srdf_adjacent = srdf_pairs(files.srdf, "Adjacent", robot);
  EXPECT_EQ(adjacent, srdf_adjacent);
  const std::set<NamePair> colliding = colliding_at_default_pose(robot);
  for (const NamePair& pair : colliding) {
    EXPECT_EQ(srdf_adjacent.count(pair), 0u) << pair.first << " - " << pair.second;
  }
  std::cout << robot_name << " without SRDF: " << adjacent.size()
            << " adjacent pairs with geometry, " << robot.checked_pairs().size() << " checked, "
            << colliding.size() << " colliding at the default pose:";
  for (const NamePair& pair : colliding) std::cout << " " << pair.first << "-" << pair.second;
  std::cout << "\n";
  return colliding;
}

TEST(RealRobots, Pr2AdjacencyWithoutSrdfIsMoveIts) {
  REQUIRE_SHARED_DATA(data);
  const RealRobot files = pr2(data);
  const std::set<NamePair> colliding = adjacency_is_moveits(files, "PR2");
  // Each is a pair the Setup Assistant found colliding at the default pose.
  const RobotModel robot = load_urdf(files.urdf, files.packages, {"test", 0, "urdf"});
  const std::set<NamePair> defaults = srdf_pairs(files.srdf, "Default", robot);
  for (const NamePair& pair : colliding) {
    EXPECT_EQ(defaults.count(pair), 1u)
        << pair.first << " - " << pair.second << " collides but is no SRDF \"Default\" pair";
  }
}

// Talos's SRDF was not written for this pose: at the zero pose its hands rest inside
// its thighs (see TalosAnswersABatch), pairs the SRDF does not list; no joint among
// the pairs that collide.
TEST(RealRobots, TalosAdjacencyWithoutSrdfIsMoveIts) {
  REQUIRE_SHARED_DATA(data);
  adjacency_is_moveits(talos(data), "Talos");
}

// A scene around a real robot: no obstacles but a floor, a rest pose as start and goal.
std::string write_scene(const testing::ScratchFolder& scratch, const RealRobot& files,
                        const std::string& robot_lines, const std::string& start_goal) {
  std::string packages;
  for (const auto& [name, folder] : files.packages) packages += name + ": '" + folder + "', ";
  packages.resize(packages.size() - 2);
  return scratch.write("real.yaml",
                       "robot:\n  urdf: '" + files.urdf + "'\n  srdf: '" + files.srdf +
                           "'\n  packages: {" + packages + "}\n" + robot_lines +
                           "obstacles:\n  - box: [20, 20, 0.1]\n    pose: {xyz: [0, 0, -2]}\n" +
                           start_goal);
}

// Checks a seeded random batch: some configurations collide (with the robot itself:
// the floor is out of reach), some are free, and the result is the same on 1 and 4
// threads.
void answers_a_batch(const Scene& scene) {
  const int n = 400;
  const std::vector<float> q = testing::sample_configurations(scene, n, 5);
  FclChecker one(scene, 1), all(scene, 4);
  std::vector<std::uint8_t> a(n), b(n);
  one.check(q.data(), n, a.data());
  all.check(q.data(), n, b.data());
  EXPECT_EQ(a, b);
  int hits = 0;
  for (std::uint8_t v : a) hits += v;
  EXPECT_GT(hits, 0) << "random joint values should sometimes self-collide";
  EXPECT_LT(hits, n);
  std::cout << scene.robot.name << ": " << hits << " of " << n
            << " random configurations collide\n";
}

TEST(RealRobots, Pr2AnswersABatch) {
  REQUIRE_SHARED_DATA(data);
  testing::ScratchFolder scratch;
  const std::string arm =
      "_shoulder_pan_joint, _shoulder_lift_joint, _upper_arm_roll_joint, "
      "_elbow_flex_joint, _forearm_roll_joint, _wrist_flex_joint, _wrist_roll_joint";
  std::string joints = "torso_lift_joint";
  for (const char* side : {"r", "l"}) {
    std::string list = arm;
    for (std::size_t at = 0; (at = list.find('_', at)) != std::string::npos; at += 2) {
      if (at == 0 || list[at - 1] == ' ') list.insert(at, side), ++at;
    }
    joints += ", " + list;
  }
  const std::string file =
      write_scene(scratch, pr2(data), "  base: planar\n  planned_joints: [" + joints + "]\n",
                  "bounds: {min: [-1, -1], max: [1, 1]}\n"
                  "start: {base: {xy: [0, 0], theta: 0}, joints: {torso_lift_joint: 0.1, "
                  "r_shoulder_pan_joint: 0, r_shoulder_lift_joint: 0, r_upper_arm_roll_joint: 0, "
                  "r_elbow_flex_joint: -0.5, r_forearm_roll_joint: 0, r_wrist_flex_joint: -0.5, "
                  "r_wrist_roll_joint: 0, l_shoulder_pan_joint: 0, l_shoulder_lift_joint: 0, "
                  "l_upper_arm_roll_joint: 0, l_elbow_flex_joint: -0.5, l_forearm_roll_joint: 0, "
                  "l_wrist_flex_joint: -0.5, l_wrist_roll_joint: 0}}\n"
                  "goal: {base: {xy: [0.5, 0], theta: 1}, joints: {torso_lift_joint: 0.2, "
                  "r_shoulder_pan_joint: -0.5, r_shoulder_lift_joint: 0, r_upper_arm_roll_joint: "
                  "0, r_elbow_flex_joint: -0.5, r_forearm_roll_joint: 0, r_wrist_flex_joint: -0.5, "
                  "r_wrist_roll_joint: 0, l_shoulder_pan_joint: 0.5, l_shoulder_lift_joint: 0, "
                  "l_upper_arm_roll_joint: 0, l_elbow_flex_joint: -0.5, l_forearm_roll_joint: 0, "
                  "l_wrist_flex_joint: -0.5, l_wrist_roll_joint: 0}}\n");
  const Scene scene = load_scene(file);
  EXPECT_EQ(scene.space.width(), 18);
  EXPECT_EQ(scene.space.dof(), 18);
  FclChecker checker(scene);
  check_start_and_goal(scene, &checker);  // the arms held forward are free
  answers_a_batch(scene);
}

TEST(RealRobots, TalosAnswersABatch) {
  REQUIRE_SHARED_DATA(data);
  testing::ScratchFolder scratch;
  const RealRobot files = talos(data);
  // Plan every joint with a value, found from the URDF itself.
  const RobotModel robot = load_urdf(files.urdf, files.packages, {"test", 0, "urdf"});
  // At the zero pose Talos's hands rest inside its thighs; lift the arms sideways.
  const std::map<std::string, double> lifted = {{"arm_left_2_joint", 0.4},
                                                {"arm_right_2_joint", -0.4}};
  std::string names, zeros;
  for (const Joint& joint : robot.joints) {
    if (!joint.is_single_dof() || joint.mimic_joint >= 0) continue;
    names += (names.empty() ? "" : ", ") + joint.name;
    const auto it = lifted.find(joint.name);
    const double rest =
        it != lifted.end() ? it->second : std::min(std::max(0.0, joint.lower), joint.upper);
    zeros += (zeros.empty() ? "" : ", ") + joint.name + ": " + std::to_string(rest);
  }
  const std::string file =
      write_scene(scratch, files, "  base: floating\n  planned_joints: [" + names + "]\n",
                  "bounds: {min: [-1, -1, 0.5], max: [1, 1, 1.5]}\n"
                  "start: {base: {xyz: [0, 0, 1], quat_wxyz: [1, 0, 0, 0]}, joints: {" +
                      zeros +
                      "}}\n"
                      "goal: {base: {xyz: [0.5, 0, 1], quat_wxyz: [1, 0, 0, 0]}, joints: {" +
                      zeros + "}}\n");
  const Scene scene = load_scene(file);
  EXPECT_EQ(scene.space.dof(), 38);
  FclChecker checker(scene);
  check_start_and_goal(scene, &checker);  // arms lifted, the rest pose is free
  answers_a_batch(scene);
}

}  // namespace
}  // namespace gplanner
