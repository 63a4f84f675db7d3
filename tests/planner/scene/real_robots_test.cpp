// The real PR2 and Talos descriptions from ../shared/data load and answer a batch.

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <random>

#include "gplanner/planner/checkers/fcl_checker.h"
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
