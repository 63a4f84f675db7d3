// Bad scenes, robots and meshes: each one is refused with an InputError whose message
// says where ("FILE:LINE: KEY: problem"), not merely that loading failed. Every case is
// a tiny self-contained scene written to a scratch folder: a box robot (an OBJ mesh, or
// a three-link URDF of box primitives) among box obstacles.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace fs = std::filesystem;
using gplanner::testing::ScratchFolder;

// A cube of side 0.2 centred at the origin, faces counter-clockwise seen from outside.
const char* const kBoxObj =
    "# cube, side 0.2\n"
    "v -0.1 -0.1 -0.1\nv 0.1 -0.1 -0.1\nv 0.1 0.1 -0.1\nv -0.1 0.1 -0.1\n"
    "v -0.1 -0.1 0.1\nv 0.1 -0.1 0.1\nv 0.1 0.1 0.1\nv -0.1 0.1 0.1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

// A rigid box robot (floating base) between two positions, an obstacle box in between.
struct MeshScene {
  std::string head = "name: tiny\n";
  std::string robot = "robot:\n  mesh: box.obj\n";
  std::string obstacles =
      "obstacles:\n"
      "  - box: [0.5, 0.5, 0.5]\n"
      "    pose: {xyz: [0, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
  std::string bounds = "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2]\n";
  std::string start = "start:\n  base: {xyz: [-1, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
  std::string goal = "goal:\n  base: {xyz: [1, 0, 0], quat_wxyz: [0, 0, 0, 1]}\n";
  std::string tail;

  std::string text() const { return head + robot + obstacles + bounds + start + goal + tail; }
};

// Three links on two prismatic joints along z: base (a 1 x 1 x 0.2 slab at the origin),
// link1 (a 0.1 cube, `lift` in [0, 1] above z = 0.5) and link2 (a 0.2 cube, `drop` in
// [-1, 0] below link1). base and link2 are not adjacent: with lift = 0 and drop = -0.5
// link2 sits inside the base slab.
const char* const kArmUrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    <collision><geometry><box size="1 1 0.2"/></geometry></collision>
  </link>
  <link name="link1">
    <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <link name="link2">
    <collision><geometry>LINK2_GEOMETRY</geometry></collision>
  </link>
  <joint name="lift" type="prismatic">
    <parent link="base"/>
    <child link="link1"/>
    <origin xyz="0 0 0.5"/>
    <axis xyz="0 0 1"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="drop" type="prismatic">
    <parent link="link1"/>
    <child link="LINK2_NAME"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1" upper="0" effort="1" velocity="1"/>
  </joint>
</robot>
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "'" << from << "' not in the text";
    return text;
  }
  return text.replace(at, from.size(), to);
}

std::string arm_urdf(const std::string& link2_geometry = "<box size=\"0.2 0.2 0.2\"/>",
                     const std::string& link2_name = "link2") {
  return replaced(replaced(kArmUrdf, "LINK2_GEOMETRY", link2_geometry), "LINK2_NAME", link2_name);
}

// A fixed-base scene for the arm, planning both joints; an obstacle far away.
struct ArmScene {
  std::string head = "name: arm\n";
  std::string robot = "robot:\n  urdf: arm.urdf\n  planned_joints: [lift, drop]\n";
  std::string obstacles = "obstacles:\n  - box: [0.2, 0.2, 0.2]\n    pose: {xyz: [3, 3, 3]}\n";
  std::string bounds;
  std::string start = "start:\n  joints: {lift: 0.5, drop: 0}\n";
  std::string goal = "goal:\n  joints: {lift: 0.8, drop: -0.2}\n";

  std::string text() const { return head + robot + obstacles + bounds + start + goal; }
};

// 1-based number of the first line of `text` containing `needle` (0 when none).
int line_of(const std::string& text, const std::string& needle) {
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.find(needle) != std::string::npos) return number;
  }
  ADD_FAILURE() << "no line holds '" << needle << "' in:\n" << text;
  return 0;
}

constexpr int kAnyLine = -1;

// What an InputError must say. The message is "FILE:LINE: KEY: problem"; `file` is the
// full path as handed to the loader, `line` 0 when the message names none (kAnyLine:
// not checked), and `also` further substrings the problem text must hold.
struct Expected {
  std::string file;
  int line = kAnyLine;
  std::string key;
  std::vector<std::string> also;
};

// Runs `load` and checks that it throws an InputError saying `expected`; the message
// is printed whenever it does not match.
::testing::AssertionResult FailsWith(const std::function<void()>& load, const Expected& expected) {
  try {
    load();
  } catch (const InputError& e) {
    const std::string message = e.what();
    auto mismatch = [&](const std::string& why) {
      return ::testing::AssertionFailure() << why << "\n  message: " << message;
    };
    if (e.where().file != expected.file) {
      return mismatch("names file '" + e.where().file + "', expected '" + expected.file + "'");
    }
    if (e.where().key != expected.key) {
      return mismatch("names key '" + e.where().key + "', expected '" + expected.key + "'");
    }
    if (expected.line != kAnyLine && e.where().line != expected.line) {
      return mismatch("names line " + std::to_string(e.where().line) + ", expected " +
                      std::to_string(expected.line));
    }
    std::string prefix = expected.file;
    if (expected.line != kAnyLine) {
      if (expected.line > 0) prefix += ":" + std::to_string(expected.line);
      prefix += ": ";
      if (!expected.key.empty()) prefix += expected.key + ": ";
      if (message.rfind(prefix, 0) != 0) return mismatch("does not start with '" + prefix + "'");
    } else {
      if (message.rfind(prefix + ":", 0) != 0) {
        return mismatch("does not start with '" + prefix + ":'");
      }
      if (!expected.key.empty() && message.find(": " + expected.key + ": ") == std::string::npos) {
        return mismatch("does not name the key '" + expected.key + "'");
      }
    }
    for (const std::string& part : expected.also) {
      if (message.find(part) == std::string::npos) return mismatch("does not say '" + part + "'");
    }
    return ::testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure()
           << "threw something other than an InputError: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

// A scratch folder holding the box mesh and the arm URDF, with the scene files written
// by each test.
class SceneErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_.write("box.obj", kBoxObj);
    folder_.write("arm.urdf", arm_urdf());
  }

  std::string write(const std::string& name, const std::string& text) const {
    return folder_.write(name, text);
  }
  std::string path(const std::string& name) const {
    return (fs::path(folder_.path()) / name).string();
  }

  // Writes `text` as scene.yaml and expects loading it to fail at `needle`'s line with
  // `key`, the problem saying each of `also`.
  ::testing::AssertionResult SceneFailsAt(const std::string& text, const std::string& needle,
                                          const std::string& key,
                                          const std::vector<std::string>& also = {}) const {
    const std::string scene = write("scene.yaml", text);
    return FailsWith([&] { load_scene(scene); }, {scene, line_of(text, needle), key, also});
  }

  ScratchFolder folder_;
};

// --- positive cases ----------------------------------------------------------------------

TEST_F(SceneErrors, ValidMeshSceneLoads) {
  const std::string scene_file = write("scene.yaml", MeshScene().text());
  const Scene scene = load_scene(scene_file);
  EXPECT_EQ(scene.name, "tiny");
  EXPECT_EQ(scene.space.base, BaseType::kFloating);
  EXPECT_EQ(scene.space.width(), 7);
  EXPECT_EQ(scene.space.dof(), 6);
  ASSERT_EQ(scene.robot.links.size(), 1u);
  EXPECT_EQ(scene.robot.triangle_count(), 12u);
  ASSERT_EQ(scene.obstacles.size(), 1u);
  EXPECT_EQ(scene.obstacles[0].mesh_S.triangle_count(), 12u);
  ASSERT_EQ(scene.start.size(), 7u);
  ASSERT_EQ(scene.goal.size(), 7u);
  EXPECT_FLOAT_EQ(scene.start[0], -1.0f);
  EXPECT_FLOAT_EQ(scene.goal[6], 1.0f);  // qz of the goal's half turn about z
  EXPECT_EQ(scene.space.base_min, Eigen::Vector3d(-2, -2, -2));
  EXPECT_EQ(scene.space.base_max, Eigen::Vector3d(2, 2, 2));

  FclChecker checker(scene, 1);
  EXPECT_NO_THROW(check_start_and_goal(scene, &checker));
  EXPECT_GE(first_collision_on_straight_line(scene, &checker), 0.0);
}

TEST_F(SceneErrors, ValidUrdfSceneLoads) {
  write("arm.srdf", R"(<?xml version="1.0"?>
<robot name="arm">
  <group name="arm"><joint name="lift"/></group>
  <disable_collisions link1="base" link2="link2" reason="Never"/>
</robot>
)");
  ArmScene arm;
  arm.robot += "  srdf: arm.srdf\n";
  const std::string scene_file = write("scene.yaml", arm.text());
  const Scene scene = load_scene(scene_file);
  EXPECT_EQ(scene.space.base, BaseType::kFixed);
  EXPECT_EQ(scene.space.width(), 2);
  EXPECT_EQ(scene.space.dof(), 2);
  ASSERT_EQ(scene.robot.links.size(), 3u);
  ASSERT_EQ(scene.robot.joints.size(), 2u);
  ASSERT_EQ(scene.space.planned_joints.size(), 2u);
  EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[0]].name, "lift");
  EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[1]].name, "drop");
  EXPECT_EQ(scene.space.lower, (std::vector<double>{0, -1}));
  EXPECT_EQ(scene.space.upper, (std::vector<double>{1, 0}));
  EXPECT_EQ(scene.start, (std::vector<float>{0.5f, 0.0f}));
  EXPECT_EQ(scene.goal, (std::vector<float>{0.8f, -0.2f}));
  // Adjacent pairs and the SRDF's base-link2 pair leave nothing to check.
  EXPECT_TRUE(scene.robot.checked_pairs().empty());
  EXPECT_EQ(scene.robot.srdf_file, path("arm.srdf"));

  FclChecker checker(scene, 1);
  EXPECT_NO_THROW(check_start_and_goal(scene, &checker));
}

TEST_F(SceneErrors, ValidPlanarUrdfSceneLoads) {
  ArmScene arm;
  arm.robot += "  base: planar\n";
  arm.bounds = "bounds:\n  min: [-1, -1]\n  max: [1, 1]\n";
  arm.start = "start:\n  base: {xy: [0, 0], theta: 0}\n  joints: {lift: 0.5, drop: 0}\n";
  arm.goal = "goal:\n  base: {xy: [0.5, 0], theta: 1}\n  joints: {lift: 0.8, drop: -0.2}\n";
  const Scene scene = load_scene(write("scene.yaml", arm.text()));
  EXPECT_EQ(scene.space.base, BaseType::kPlanar);
  EXPECT_EQ(scene.space.width(), 5);
  EXPECT_EQ(scene.space.dof(), 5);
  // base and link2 are a checked pair without an SRDF.
  ASSERT_EQ(scene.robot.checked_pairs().size(), 1u);
}

// --- the scene file itself ---------------------------------------------------------------

TEST_F(SceneErrors, MissingSceneFile) {
  const std::string missing = path("nosuch.yaml");
  EXPECT_TRUE(FailsWith([&] { load_scene(missing); }, {missing, 0, "", {"does not exist"}}));
}

TEST_F(SceneErrors, SceneFileThatIsAFolder) {
  fs::create_directories(path("folder.yaml"));
  const std::string folder = path("folder.yaml");
  EXPECT_TRUE(FailsWith([&] { load_scene(folder); }, {folder, 0, "", {}}));
}

TEST_F(SceneErrors, UnreadableSceneFile) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads files whatever their permissions";
  const std::string scene = write("scene.yaml", MeshScene().text());
  ASSERT_EQ(chmod(scene.c_str(), 0), 0);
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {scene, 0, "", {"cannot be read"}}));
}

TEST_F(SceneErrors, MalformedYaml) {
  MeshScene s;
  s.bounds = "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2\nstart_typo: here\n";
  // The unclosed flow sequence is reported where yaml-cpp gives up: at the next key.
  const std::string text = s.text();
  const std::string scene = write("scene.yaml", text);
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); },
                        {scene, line_of(text, "start_typo"), "yaml", {"malformed YAML"}}));
}

TEST_F(SceneErrors, MalformedYamlBadIndentation) {
  MeshScene s;
  s.robot = "robot:\n    mesh: box.obj\n  colour: red\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "colour: red", "yaml", {"malformed YAML"}));
}

TEST_F(SceneErrors, EmptySceneFile) {
  const std::string scene = write("scene.yaml", "");
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {scene, kAnyLine, "", {"expected a map"}}));
}

// --- unknown keys ------------------------------------------------------------------------

TEST_F(SceneErrors, UnknownTopLevelKey) {
  MeshScene s;
  s.tail = "colour: red\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "colour", "colour", {"unknown key", "robot"}));
}

TEST_F(SceneErrors, UnknownRobotKey) {
  MeshScene s;
  s.robot += "  colour: red\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "colour", "robot.colour", {"unknown key", "urdf"}));
}

TEST_F(SceneErrors, UnknownObstacleKey) {
  MeshScene s;
  s.obstacles += "  - sphere: 0.1\n    colour: red\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "colour", "obstacles[1].colour", {"unknown key"}));
  s = MeshScene();
  s.obstacles = "obstacles:\n  - box: [0.5, 0.5, 0.5]\n    colour: red\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "colour", "obstacles[0].colour", {"unknown key", "pose"}));
}

TEST_F(SceneErrors, UnknownStartBaseKey) {
  MeshScene s;
  s.start = "start:\n  base:\n    xyz: [-1, 0, 0]\n    quat_wxyz: [1, 0, 0, 0]\n    foo: 1\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "foo", "start.base.foo", {"unknown key", "xyz"}));
}

TEST_F(SceneErrors, UnknownPoseKey) {
  MeshScene s;
  s.obstacles =
      "obstacles:\n  - box: [0.5, 0.5, 0.5]\n    pose: {xyz: [0, 0, 0], rpy: [0, 0, 1]}\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "rpy", "obstacles[0].pose.rpy", {"unknown key"}));
}

TEST_F(SceneErrors, UnknownPlannerSetting) {
  MeshScene s;
  s.tail = "planner:\n  seed: 2\n  nosuch_setting: 3\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "nosuch_setting", "planner.nosuch_setting",
                           {"unknown planner setting"}));
}

TEST_F(SceneErrors, PlannerSettingOutOfRange) {
  const std::vector<std::vector<std::string>> cases = {
      {"time_limit_s: 0\n", "time_limit_s: 0", "planner.time_limit_s", "positive"},
      {"edge_resolution: 1.5\n", "edge_resolution: 1.5", "planner.edge_resolution", "[1e-5, 1]"},
      // Integers given as doubles were cast: -1 wrapped, 1e30 overflowed, 1.9 became 1.
      {"seed: -1\n", "seed: -1", "planner.seed", "whole number from 0 to 9007199254740992"},
      {"seed: 1e30\n", "seed: 1e30", "planner.seed", "whole number from 0 to 9007199254740992"},
      {"seed: 1.9\n", "seed: 1.9", "planner.seed", "whole number from 0 to 9007199254740992"},
      {"shortcut: {candidates: 1e30}\n", "candidates: 1e30", "planner.shortcut.candidates",
       "whole number from 1 to 1e6"},
      // Billions of samples an edge: a hang, not an answer.
      {"edge_resolution: 1e-9\n", "edge_resolution: 1e-9", "planner.edge_resolution",
       "1e5 at most"},
      {"max_displacement: -0.1\n", "max_displacement: -0.1", "planner.max_displacement", "0"},
      {"roadmap: {neighbors: 100}\n", "neighbors: 100", "planner.roadmap.neighbors", "1 to 64"},
      {"roadmap: {lazy_batch_paths: 0}\n", "lazy_batch_paths: 0",
       "planner.roadmap.lazy_batch_paths", "1 to 4096"},
      {"roadmap:\n    milestones: 2.5\n", "milestones: 2.5", "planner.roadmap.milestones",
       "whole number"},
      {"shortcut: {rounds: -1}\n", "rounds: -1", "planner.shortcut.rounds", "whole number"},
      {"distance_weights: {rotation: -2}\n", "rotation: -2", "planner.distance_weights.rotation",
       "0 or more"}};
  for (const auto& c : cases) {
    MeshScene s;
    s.tail = "planner:\n  " + c[0];
    EXPECT_TRUE(SceneFailsAt(s.text(), c[1], c[2], {c[3]})) << c[0];
  }
}

// max_displacement in range but so small against the robot's reach that an edge would
// take billions of samples: refused with the estimate and the least value accepted.
TEST_F(SceneErrors, MaxDisplacementAskingForTooManySamplesPerEdge) {
  MeshScene s;
  s.tail = "planner:\n  max_displacement: 1.0e-8\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "max_displacement: 1.0e-8", "planner.max_displacement",
                           {"samples per edge", "more than 100000", "give at least"}));
  s.tail = "planner:\n  max_displacement: 0.01\n";
  EXPECT_NO_THROW(load_scene(write("fine.yaml", s.text())));
}

TEST_F(SceneErrors, MissingRequiredKey) {
  MeshScene s;
  s.goal = "";
  const std::string text = s.text();
  const std::string scene = write("scene.yaml", text);
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {scene, kAnyLine, "goal", {"missing"}}));
}

TEST_F(SceneErrors, KeyThatIsNotAName) {
  MeshScene s;
  s.tail = "? [a, b]\n: 1\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "[a, b]", "", {"expected a key name"}));
  s = MeshScene();
  s.robot += "  ? {a: 1}\n  : 1\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "{a: 1}", "robot", {"expected a key name"}));
}

// --- wrong types -------------------------------------------------------------------------

TEST_F(SceneErrors, StringWhereANumberGoes) {
  MeshScene s;
  s.bounds = "bounds:\n  min: [-2, wide, -2]\n  max: [2, 2, 2]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "wide", "bounds.min[1]", {"expected a number", "'wide'"}));
  s = MeshScene();
  s.obstacles = "obstacles:\n  - sphere: big\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "big", "obstacles[0].sphere", {"expected a number"}));
}

TEST_F(SceneErrors, MapWhereAListGoes) {
  MeshScene s;
  s.obstacles = "obstacles:\n  box: [0.5, 0.5, 0.5]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "box:", "obstacles", {"expected a list"}));
  s = MeshScene();
  s.start = "start:\n  base:\n    xyz: {x: -1, y: 0, z: 0}\n    quat_wxyz: [1, 0, 0, 0]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "xyz: {x", "start.base.xyz",
                           {"expected a list of 3 numbers", "a map"}));
}

TEST_F(SceneErrors, ListWhereAStringGoes) {
  MeshScene s;
  s.robot = "robot:\n  mesh: [box.obj]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "mesh:", "robot.mesh", {"expected a string"}));
}

TEST_F(SceneErrors, WrongCountOfNumbers) {
  MeshScene s;
  s.bounds = "bounds:\n  min: [-2, -2]\n  max: [2, 2, 2]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "min:", "bounds.min", {"expected a list of 3 numbers"}));
}

TEST_F(SceneErrors, UnknownBaseType) {
  ArmScene arm;
  arm.robot += "  base: hovering\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "hovering", "robot.base", {"'hovering'", "planar"}));
}

// --- numbers that are not numbers, ranges that are not ranges ----------------------------

TEST_F(SceneErrors, NanNumber) {
  MeshScene s;
  s.start = "start:\n  base: {xyz: [.nan, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), ".nan", "start.base.xyz[0]", {"finite"}));
}

TEST_F(SceneErrors, InfiniteNumber) {
  MeshScene s;
  s.obstacles = "obstacles:\n  - box: [0.5, .inf, 0.5]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), ".inf", "obstacles[0].box[1]", {"finite"}));
  s = MeshScene();
  s.bounds = "bounds:\n  min: [-2, -2, -.inf]\n  max: [2, 2, 2]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "-.inf", "bounds.min[2]", {"finite"}));
}

TEST_F(SceneErrors, NanJointValue) {
  ArmScene arm;
  arm.goal = "goal:\n  joints: {lift: .NaN, drop: 0}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), ".NaN", "goal.joints.lift", {"finite"}));
}

TEST_F(SceneErrors, InvertedBounds) {
  MeshScene s;
  s.bounds = "bounds:\n  min: [-2, 2, -2]\n  max: [2, -2, 2]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "min:", "bounds.min", {"inverted", "axis y"}));
}

TEST_F(SceneErrors, EmptyBounds) {
  MeshScene s;
  s.bounds = "bounds:\n  min: [-2, -2, 1]\n  max: [2, 2, 1]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "min:", "bounds.min", {"axis z"}));
}

TEST_F(SceneErrors, InvertedJointLimits) {
  ArmScene arm;
  arm.robot += "  joint_limits: {lift: [0.8, 0.2]}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "joint_limits", "robot.joint_limits.lift", {"inverted"}));
}

TEST_F(SceneErrors, JointLimitsWiderThanTheUrdf) {
  ArmScene arm;
  arm.robot += "  joint_limits: {lift: [-0.5, 0.5]}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "joint_limits", "robot.joint_limits.lift", {"only narrow"}));
}

TEST_F(SceneErrors, ZeroLengthStartQuaternion) {
  MeshScene s;
  s.start = "start:\n  base:\n    xyz: [-1, 0, 0]\n    quat_wxyz: [0, 0, 0, 0]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "quat_wxyz: [0, 0, 0, 0]", "start.base.quat_wxyz",
                           {"zero-length quaternion"}));
}

TEST_F(SceneErrors, ZeroLengthObstacleQuaternion) {
  MeshScene s;
  s.obstacles = "obstacles:\n  - box: [0.5, 0.5, 0.5]\n    pose:\n      quat_wxyz: [0, 0, 0, 0]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "quat_wxyz", "obstacles[0].pose.quat_wxyz",
                           {"zero-length quaternion"}));
}

TEST_F(SceneErrors, NonPositiveObstacleSize) {
  MeshScene s;
  s.obstacles = "obstacles:\n  - box: [0.5, 0, 0.5]\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "box:", "obstacles[0].box", {"positive"}));
}

// --- URDF and SRDF -----------------------------------------------------------------------

TEST_F(SceneErrors, UnknownPackageInUrdfMesh) {
  const std::string text = arm_urdf("<mesh filename=\"package://nosuch_pkg/box.obj\"/>");
  const std::string urdf = write("arm.urdf", text);
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(
      FailsWith([&] { load_scene(scene); }, {urdf,
                                             line_of(text, "<mesh filename="),
                                             "link 'link2' collision",
                                             {"unknown package 'nosuch_pkg'", "packages"}}));
}

TEST_F(SceneErrors, KnownPackageInUrdfMeshLoads) {
  write("meshes/box.obj", kBoxObj);
  write("arm.urdf", arm_urdf("<mesh filename=\"package://tiny/meshes/box.obj\"/>"));
  ArmScene arm;
  arm.robot += "  packages: {tiny: .}\n";
  const Scene scene = load_scene(write("scene.yaml", arm.text()));
  EXPECT_EQ(scene.robot.links[scene.robot.find_link("link2")].collision.triangle_count(), 12u);
}

TEST_F(SceneErrors, MalformedPackageUri) {
  const std::string text = arm_urdf("<mesh filename=\"package:///meshes/box.obj\"/>");
  const std::string urdf = write("arm.urdf", text);
  ArmScene arm;
  arm.robot += "  packages: {tiny: .}\n";
  const std::string scene = write("scene.yaml", arm.text());
  EXPECT_TRUE(
      FailsWith([&] { load_scene(scene); }, {urdf,
                                             line_of(text, "<mesh filename="),
                                             "link 'link2' collision",
                                             {"malformed URI", "package:///meshes/box.obj"}}));
}

TEST_F(SceneErrors, PackageFolderMissing) {
  ArmScene arm;
  arm.robot += "  packages: {tiny: nosuch_folder}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "packages", "robot.packages.tiny", {"does not exist"}));
}

TEST_F(SceneErrors, UrdfMeshMissing) {
  const std::string text = arm_urdf("<mesh filename=\"meshes/nosuch.obj\"/>");
  const std::string urdf = write("arm.urdf", text);
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {urdf,
                                                     line_of(text, "<mesh filename="),
                                                     "link 'link2' collision",
                                                     {"nosuch.obj", "does not exist"}}));
}

TEST_F(SceneErrors, UrdfNotWellFormed) {
  // link1's <collision> is never closed: the parser stops at link1's </link>.
  std::string text = arm_urdf();
  text = replaced(text, "<box size=\"0.1 0.1 0.1\"/></geometry></collision>",
                  "<box size=\"0.1 0.1 0.1\"/></geometry>");
  const std::string urdf = write("arm.urdf", text);
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(
      FailsWith([&] { load_scene(scene); }, {urdf, kAnyLine, "xml", {"not well-formed XML"}}));
  // The line is that of the unclosed element or of the closing tag that does not match.
  const int unclosed = line_of(text, "<box size=\"0.1 0.1 0.1\"/></geometry>");
  try {
    load_scene(scene);
  } catch (const InputError& e) {
    EXPECT_GE(e.where().line, unclosed) << e.what();
    EXPECT_LE(e.where().line, unclosed + 1) << e.what();
  }
}

TEST_F(SceneErrors, UrdfJointNamesMissingLink) {
  const std::string text = arm_urdf("<box size=\"0.2 0.2 0.2\"/>", "gripper");
  const std::string urdf = write("arm.urdf", text);
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(FailsWith(
      [&] { load_scene(scene); },
      {urdf, line_of(text, "<joint name=\"drop\""), "joint 'drop'", {"gripper", "not defined"}}));
}

// Broken trees: each a line-numbered error before urdfdom reads the file.
TEST_F(SceneErrors, UrdfThatIsNoTree) {
  const std::string base = arm_urdf();
  const std::string end = "</robot>";
  const std::vector<std::vector<std::string>> cases = {
      // extra XML before </robot>, the key and line it must name, and what it must say
      {"<joint name=\"back\" type=\"fixed\"><parent link=\"link2\"/><child link=\"base\"/></joint>",
       "link 'base'", "<link name=\"base\">", "cycle"},
      {"<joint name=\"twice\" type=\"fixed\"><parent link=\"base\"/><child "
       "link=\"link2\"/></joint>",
       "joint 'twice'", "<joint name=\"twice\"", "already the child"},
      {"<joint name=\"self\" type=\"fixed\"><parent link=\"base\"/><child link=\"base\"/></joint>",
       "joint 'self'", "<joint name=\"self\"", "itself"},
      {"<link name=\"link1\"/>", "link 'link1'", "<link name=\"link1\"/>", "defined twice"},
      {"<link name=\"loose\"/>", "robot", "<robot name", "several root links"},
      {"<joint name=\"open\" type=\"fixed\"><parent link=\"base\"/></joint>", "joint 'open'",
       "<joint name=\"open\"", "child link"}};
  for (const auto& c : cases) {
    std::string text = base;
    text.replace(text.rfind(end), end.size(), c[0] + "\n" + end);
    const std::string urdf = write("arm.urdf", text);
    const std::string scene = write("scene.yaml", ArmScene().text());
    EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {urdf, line_of(text, c[2]), c[1], {c[3]}}))
        << c[0];
  }
}

TEST_F(SceneErrors, UrdfNotARobot) {
  const std::string urdf = write("arm.urdf", "<?xml version=\"1.0\"?>\n<model name=\"arm\"/>\n");
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); }, {urdf, kAnyLine, "robot", {"no <robot>"}}));
}

TEST_F(SceneErrors, UrdfFileMissing) {
  ArmScene arm;
  arm.robot = "robot:\n  urdf: nosuch.urdf\n  planned_joints: [lift, drop]\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "nosuch.urdf", "robot.urdf", {"does not exist"}));
}

// As srdfdom does: disable_collisions pairs naming links the URDF lacks are skipped,
// with one notice listing them; the others apply (issue 31).
TEST_F(SceneErrors, SrdfPairsNamingLinksTheUrdfLacksAreSkippedWithOneNotice) {
  const std::string text = R"(<?xml version="1.0"?>
<robot name="arm">
  <disable_collisions link1="base" link2="link1" reason="Adjacent"/>
  <disable_collisions link1="link1" link2="gripper" reason="Never"/>
  <disable_collisions link1="camera" link2="link2" reason="Never"/>
</robot>
)";
  const std::string srdf = write("arm.srdf", text);
  ArmScene arm;
  arm.robot += "  srdf: arm.srdf\n";
  const Scene scene = load_scene(write("scene.yaml", arm.text()));
  int mentions = 0;
  for (const std::string& notice : scene.notices) {
    if (notice.find("disable_collisions") == std::string::npos) continue;
    ++mentions;
    EXPECT_EQ(notice.rfind(srdf + ": 2 disable_collisions link name(s)", 0), 0u) << notice;
    EXPECT_NE(notice.find("gripper (line " + std::to_string(line_of(text, "gripper")) + ")"),
              std::string::npos)
        << notice;
    EXPECT_NE(notice.find("camera (line " + std::to_string(line_of(text, "camera")) + ")"),
              std::string::npos)
        << notice;
    EXPECT_NE(notice.find("arm.urdf"), std::string::npos) << notice;
  }
  EXPECT_EQ(mentions, 1);
  const int base = scene.robot.find_link("base"), link1 = scene.robot.find_link("link1");
  EXPECT_NE(std::find(scene.robot.disabled_pairs.begin(), scene.robot.disabled_pairs.end(),
                      std::make_pair(std::min(base, link1), std::max(base, link1))),
            scene.robot.disabled_pairs.end());
}

TEST_F(SceneErrors, SrdfNotWellFormed) {
  const std::string text =
      "<?xml version=\"1.0\"?>\n<robot name=\"arm\">\n  <group name=\"a\">\n</robot>\n";
  const std::string srdf = write("arm.srdf", text);
  ArmScene arm;
  arm.robot += "  srdf: arm.srdf\n";
  const std::string scene = write("scene.yaml", arm.text());
  EXPECT_TRUE(
      FailsWith([&] { load_scene(scene); }, {srdf, kAnyLine, "xml", {"not well-formed XML"}}));
}

TEST_F(SceneErrors, PlannedJointUnknown) {
  ArmScene arm;
  arm.robot = "robot:\n  urdf: arm.urdf\n  planned_joints: [lift, elbow]\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "planned_joints", "robot.planned_joints[1]",
                           {"no joint 'elbow'", "arm.urdf"}));
}

TEST_F(SceneErrors, StartNamesJointNotPlanned) {
  ArmScene arm;
  arm.start = "start:\n  joints: {lift: 0.5, drop: 0, elbow: 1}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "elbow", "start.joints.elbow", {"not a planned joint"}));
}

// --- meshes ------------------------------------------------------------------------------

TEST_F(SceneErrors, RobotMeshMissing) {
  MeshScene s;
  s.robot = "robot:\n  mesh: meshes/nosuch.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "nosuch.obj", "robot.mesh", {"nosuch.obj", "does not exist"}));
}

TEST_F(SceneErrors, ObstacleMeshMissing) {
  MeshScene s;
  s.obstacles = "obstacles:\n  - mesh: nosuch_room.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "nosuch_room", "obstacles[0].mesh",
                           {"nosuch_room.obj", "does not exist"}));
}

TEST_F(SceneErrors, MeshWithOnlyVertices) {
  write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  MeshScene s;
  s.robot = "robot:\n  mesh: points.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "points.obj", "robot.mesh", {"points.obj", "no triangles"}));
}

TEST_F(SceneErrors, MeshWithOnlyPointsAndLines) {
  write("wire.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\nl 1 2 3 1\n");
  MeshScene s;
  s.obstacles = "obstacles:\n  - mesh: wire.obj\n";
  EXPECT_TRUE(
      SceneFailsAt(s.text(), "wire.obj", "obstacles[0].mesh", {"wire.obj", "no triangles"}));
}

TEST_F(SceneErrors, MeshWithOnlyDegenerateFaces) {
  write("flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n");
  MeshScene s;
  s.robot = "robot:\n  mesh: flat.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "flat.obj", "robot.mesh", {"flat.obj", "no triangles"}));
}

TEST_F(SceneErrors, UrdfMeshWithNoTriangles) {
  write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  const std::string text = arm_urdf("<mesh filename=\"points.obj\"/>");
  const std::string urdf = write("arm.urdf", text);
  const std::string scene = write("scene.yaml", ArmScene().text());
  EXPECT_TRUE(FailsWith(
      [&] { load_scene(scene); },
      {urdf, line_of(text, "<mesh filename="), "link 'link2' collision", {"points.obj"}}));
}

// --- start and goal ----------------------------------------------------------------------

TEST_F(SceneErrors, StartOutsideBounds) {
  MeshScene s;
  s.start = "start:\n  base: {xyz: [-1, 0, 2.5], quat_wxyz: [1, 0, 0, 0]}\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "xyz: [-1, 0, 2.5]", "start", {"z = 2.5", "bounds"}));
}

TEST_F(SceneErrors, GoalOutsideJointLimits) {
  ArmScene arm;
  arm.goal = "goal:\n  joints: {lift: 1.5, drop: -0.2}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "lift: 1.5", "goal", {"lift = 1.5", "limits [0, 1]"}));
}

TEST_F(SceneErrors, GoalOutsideNarrowedJointLimits) {
  ArmScene arm;
  arm.robot += "  joint_limits: {lift: [0, 0.6]}\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "lift: 0.8", "goal", {"lift = 0.8", "limits [0, 0.6]"}));
}

TEST_F(SceneErrors, StartInCollision) {
  MeshScene s;
  s.start = "start:\n  base: {xyz: [0.2, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
  const std::string text = s.text();
  const std::string scene_file = write("scene.yaml", text);
  const Scene scene = load_scene(scene_file);  // bounds and limits are fine
  FclChecker checker(scene, 1);
  EXPECT_TRUE(FailsWith([&] { check_start_and_goal(scene, &checker); },
                        {scene_file,
                         line_of(text, "xyz: [0.2, 0, 0]"),
                         "start",
                         {"start configuration is in collision", "fcl",
                          "and obstacle 'box' (obstacles[0]) collide"}}));
}

TEST_F(SceneErrors, GoalInSelfCollision) {
  // No obstacle near: the goal collides only because link2 drops into the base slab,
  // which is not adjacent to it.
  ArmScene arm;
  arm.goal = "goal:\n  joints: {lift: 0, drop: -0.5}\n";
  const std::string text = arm.text();
  const std::string scene_file = write("scene.yaml", text);
  const Scene scene = load_scene(scene_file);
  ASSERT_EQ(scene.robot.checked_pairs().size(), 1u);
  FclChecker checker(scene, 1);
  EXPECT_FALSE(checker.in_collision(scene.start.data()));
  EXPECT_TRUE(
      FailsWith([&] { check_start_and_goal(scene, &checker); },
                {scene_file,
                 line_of(text, "drop: -0.5"),
                 "goal",
                 {"goal configuration is in collision", "link 'base' and link 'link2' collide"}}));

  // The same goal is accepted once the SRDF disables the pair.
  write("arm.srdf",
        "<robot name=\"arm\">\n  <disable_collisions link1=\"base\" link2=\"link2\"/>\n</robot>\n");
  arm.robot += "  srdf: arm.srdf\n";
  const Scene relaxed = load_scene(write("scene.yaml", arm.text()));
  FclChecker relaxed_checker(relaxed, 1);
  EXPECT_NO_THROW(check_start_and_goal(relaxed, &relaxed_checker));
}

// --- YAML structure (issue 19) -----------------------------------------------------------

TEST_F(SceneErrors, DuplicateKeyNamesBothLines) {
  MeshScene s;
  s.tail = "planner:\n  seed: 3\n  seed: 4\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "seed: 4", "planner.seed", {"given twice", "keep the one"}));
  MeshScene top;
  top.tail = "name: other\n";
  EXPECT_TRUE(SceneFailsAt(top.text(), "name: other", "name", {"given twice in one map (lines 1 and"}));
  MeshScene nested;
  nested.start =
      "start:\n  base:\n    xyz: [-1, 0, 0]\n    xyz: [1, 0, 0]\n    quat_wxyz: [1, 0, 0, 0]\n";
  EXPECT_TRUE(SceneFailsAt(nested.text(), "    xyz: [1", "start.base.xyz", {"given twice"}));
}

TEST_F(SceneErrors, SecondDocumentIsRefused) {
  MeshScene s;
  s.tail = "---\nname: second\n";
  const std::string text = s.text();
  const std::string scene = write("scene.yaml", text);
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); },
                        {scene, kAnyLine, "", {"more than one YAML document"}}));
}

TEST_F(SceneErrors, AnchorsAndAliasesInPlannerSettingsAreRefused) {
  MeshScene s;
  s.tail = "planner:\n  roadmap: &r {milestones: 10}\n  shortcut: *r\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "roadmap: &r", "planner.roadmap", {"not allowed"}));
  // 1 KB of aliases to empty maps: refused at once, not walked 10^9 times.
  std::string bomb = "planner:\n  a0: &a0 {}\n";
  for (int i = 1; i < 30; ++i) {
    bomb += "  a" + std::to_string(i) + ": &a" + std::to_string(i) + " [*a" +
            std::to_string(i - 1) + ", *a" + std::to_string(i - 1) + "]\n";
  }
  MeshScene b;
  b.tail = bomb;
  EXPECT_TRUE(SceneFailsAt(b.text(), "a0: &a0", "planner.a0", {"not allowed"}));
}

TEST_F(SceneErrors, AliasesThatExpandTooFarAreRefused) {
  // A billion laughs outside the settings: each level doubles the one before.
  MeshScene s;
  s.tail = "laughs:\n  - &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i < 12; ++i) {
    s.tail += "  - &l" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) s.tail += std::string(k ? ", " : "") + "*l" + std::to_string(i - 1);
    s.tail += "]\n";
  }
  const std::string scene = write("scene.yaml", s.text());
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); },
                        {scene, kAnyLine, "laughs[5][7]",
                         {"expand the file to more than 1000000 nodes"}}));
}

TEST_F(SceneErrors, AliasedObstaclesLoad) {
  MeshScene s;
  s.obstacles = "obstacles:\n  - &wall {mesh: box.obj, pose: {xyz: [0, 0, 0]}}\n";
  for (int i = 0; i < 200; ++i) s.obstacles += "  - *wall\n";
  const Scene scene = load_scene(write("scene.yaml", s.text()));
  EXPECT_EQ(scene.obstacles.size(), 201u);
  EXPECT_EQ(scene.obstacles[200].mesh_S.triangle_count(), 12u);
}

TEST_F(SceneErrors, TabIndentationIsNamed) {
  MeshScene s;
  s.robot = "robot:\n\tmesh: box.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "\tmesh", "yaml", {"tabs cannot indent YAML; use spaces"}));
}

TEST_F(SceneErrors, NestingBeyondTheDepthGuardIsNamed) {
  MeshScene s;
  s.tail = "description: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  const std::string scene = write("scene.yaml", s.text());
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); },
                        {scene, kAnyLine, "yaml", {"nested more than", "remove the extra nesting"}}));
}

TEST_F(SceneErrors, HugeScalarIsEchoedAsAnExcerpt) {
  MeshScene s;
  s.tail = "planner:\n  seed: " + std::string(4 * 1024 * 1024, '9') + "x\n";
  const std::string scene = write("scene.yaml", s.text());
  try {
    load_scene(scene);
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_LT(std::string(e.what()).size(), scene.size() + 300) << e.what();
    EXPECT_NE(std::string(e.what()).find("bytes)"), std::string::npos) << e.what();
  }
}

// A key longer than YAML allows an implicit key is said so (issue 32: "illegal map value").
TEST_F(SceneErrors, KeyLongerThanYamlAllowsIsSaidSo) {
  const std::string text = "name: long\n" + std::string(1100, 'k') + ": 3\n";
  const std::string scene = write("scene.yaml", text);
  EXPECT_TRUE(FailsWith([&] { load_scene(scene); },
                        {scene, 2, "yaml", {"a key longer than 1,024 characters", "shorten it"}}));
}

TEST_F(SceneErrors, QuaternionWithHugePartsIsNormalisedNotOverflowed) {
  MeshScene s;
  s.start = "start:\n  base: {xyz: [-1, 0, 0], quat_wxyz: [1e308, 1e308, 0, 0]}\n";
  const Scene scene = load_scene(write("scene.yaml", s.text()));
  EXPECT_NEAR(scene.start[3], std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(scene.start[4], std::sqrt(0.5), 1e-6);
}

TEST_F(SceneErrors, TooManyObstaclesAreRefusedAtOnce) {
  MeshScene s;
  s.obstacles = "obstacles:\n";
  for (int i = 0; i <= 10000; ++i) s.obstacles += "- {sphere: 0.1}\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "- {sphere", "obstacles",
                           {"10001 obstacles, more than the 10000"}));
}

TEST_F(SceneErrors, MeshThatIsNoRegularFileIsNamedForWhatItIs) {
  fs::create_directories(path("folder.obj"));
  ASSERT_EQ(mkfifo(path("fifo.obj").c_str(), 0600), 0);
  MeshScene s;
  s.obstacles = "obstacles:\n  - mesh: folder.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "folder.obj", "obstacles[0].mesh", {"is a folder"}));
  s.obstacles = "obstacles:\n  - mesh: fifo.obj\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "fifo.obj", "obstacles[0].mesh", {"is a FIFO"}));
  s.obstacles = "obstacles:\n  - mesh: /dev/zero\n";
  EXPECT_TRUE(SceneFailsAt(s.text(), "/dev/zero", "obstacles[0].mesh", {"is a device"}));
  fs::create_symlink(path("loop.urdf"), path("loop.urdf"));
  ArmScene arm;
  arm.robot = "robot:\n  urdf: loop.urdf\n";
  EXPECT_TRUE(SceneFailsAt(arm.text(), "loop.urdf", "robot.urdf", {"symbolic link loop"}));
}

}  // namespace
}  // namespace gplanner
