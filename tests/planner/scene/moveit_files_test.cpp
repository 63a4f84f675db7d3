// MoveIt's files in a scene (planner/src/scene/moveit_files, docs/scenes.md "MoveIt
// files"): a planning scene's objects placed as MoveIt places them (object pose, then
// primitive and mesh poses; quaternions [x, y, z, w]), its allowed collisions and joint
// values applied, a motion plan request's group, start and joint goal; the first problem
// of every MotionBenchMaker Panda scenario against values read from its files by hand;
// and every mistake refused naming the file, the line and the key.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::ScratchFolder;

const char* const kArmUrdf = R"(<robot name="arm">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><origin xyz="0 0 0.15"/><geometry><box size="0.05 0.05 0.3"/></geometry></collision></link>
  <link name="lower"><collision><origin xyz="0 0 0.15"/><geometry><cylinder radius="0.02" length="0.3"/></geometry></collision></link>
  <link name="finger"><collision><geometry><box size="0.02 0.02 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
  <joint name="grip" type="prismatic"><parent link="lower"/><child link="finger"/>
    <origin xyz="0 0 0.3"/><axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
</robot>
)";

const char* const kArmSrdf = R"(<?xml version="1.0"?>
<robot name="arm">
  <group name="arm"><chain base_link="base" tip_link="lower"/></group>
  <group name="hand"><joint name="grip"/></group>
  <group name="everything"><group name="arm"/><group name="hand"/></group>
</robot>
)";

// Within the arm's reach (obstacles beyond it are dropped): a box placed by an object
// pose (a quarter turn about z, at x = 0.3) and a primitive pose (0.1 along its own x),
// in the world at (0.3, 0.1, 0.2); a sphere by type number 2; a cylinder [height 0.4,
// radius 0.1]; a mesh of one triangle.
const char* const kPlanningScene = R"(name: test
robot_state:
  joint_state:
    name: [shoulder, elbow, grip, nosuch]
    position: [0.1, 0.2, 0.03, 5]
allowed_collision_matrix:
  entry_names: [base, lower, table]
  entry_values:
    - [false, true, false]
    - [true, false, true]
    - [false, true, false]
world:
  collision_objects:
    - id: table
      header: {frame_id: world}
      pose:
        position: [0.3, 0, 0.2]
        orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]
      primitives:
        - type: box
          dimensions: [0.2, 0.3, 0.4]
      primitive_poses:
        - position: {x: 0.1, y: 0, z: 0}
          orientation: {x: 0, y: 0, z: 0, w: 1}
    - id: ball
      primitives:
        - {type: 2, dimensions: [0.1]}
      primitive_poses:
        - {position: [-0.3, -0.3, 0.3], orientation: [0, 0, 0, 1]}
    - id: can
      primitives:
        - {type: cylinder, dimensions: [0.4, 0.1]}
      primitive_poses:
        - {position: [0, -0.3, 0.3], orientation: [0, 0, 0, 1]}
    - id: sheet
      meshes:
        - vertices: [[0.3, 0.3, 0.3], [0.4, 0.3, 0.3], {x: 0.3, y: 0.4, z: 0.3}]
          triangles: [{vertex_indices: [0, 1, 2]}]
      mesh_poses:
        - {position: [0, 0, 0], orientation: [0, 0, 0, 1]}
)";

const char* const kRequest = R"(group_name: arm
allowed_planning_time: 5
start_state:
  joint_state:
    name: [shoulder]
    position: [-0.5]
goal_constraints:
  - joint_constraints:
      - {joint_name: shoulder, position: 0.7, tolerance_above: 0.001, tolerance_below: 0.001, weight: 1}
      - {joint_name: elbow, position: -0.3}
)";

struct MoveItCase {
  ScratchFolder folder;
  std::string planning_scene = kPlanningScene;
  std::string request = kRequest;
  std::string scene_extra;  // more keys of the gplanner scene file

  std::string write() const {
    folder.write("arm.urdf", kArmUrdf);
    folder.write("arm.srdf", kArmSrdf);
    folder.write("world.yaml", planning_scene);
    folder.write("request.yaml", request);
    return folder.write("scene.yaml",
                        "name: moveit_arm\nrobot:\n  urdf: arm.urdf\n  srdf: arm.srdf\n"
                        "moveit:\n  scene: world.yaml\n  request: request.yaml\n" +
                            scene_extra);
  }
};

const Obstacle& obstacle(const Scene& scene, const std::string& name) {
  for (const Obstacle& o : scene.obstacles)
    if (o.name == name) return o;
  ADD_FAILURE() << "no obstacle " << name;
  return scene.obstacles.at(0);
}

TEST(MoveItFiles, ObjectsArePlacedAsMoveItPlacesThem) {
  MoveItCase c;
  const Scene scene = load_scene(c.write());
  ASSERT_EQ(scene.obstacles.size(), 4u);
  const Obstacle& table = obstacle(scene, "table");
  EXPECT_EQ(table.shape, ObstacleShape::kBox);
  EXPECT_TRUE(table.dimensions.isApprox(Eigen::Vector3d(0.2, 0.3, 0.4)));
  EXPECT_TRUE(table.X_SO.translation().isApprox(Eigen::Vector3d(0.3, 0.1, 0.2), 1e-12))
      << table.X_SO.translation().transpose();
  // The box's own x axis points along the world's y (a quarter turn about z).
  EXPECT_TRUE(table.X_SO.linear().col(0).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));
  const Obstacle& ball = obstacle(scene, "ball");
  EXPECT_EQ(ball.shape, ObstacleShape::kSphere);
  EXPECT_DOUBLE_EQ(ball.dimensions.x(), 0.1);
  EXPECT_TRUE(ball.X_SO.translation().isApprox(Eigen::Vector3d(-0.3, -0.3, 0.3)));
  const Obstacle& can = obstacle(scene, "can");
  EXPECT_EQ(can.shape, ObstacleShape::kCylinder);
  EXPECT_DOUBLE_EQ(can.dimensions.x(), 0.1);  // radius
  EXPECT_DOUBLE_EQ(can.dimensions.y(), 0.4);  // length (MoveIt's height)
  const Obstacle& sheet = obstacle(scene, "sheet");
  EXPECT_EQ(sheet.shape, ObstacleShape::kMesh);
  ASSERT_EQ(sheet.mesh_S.triangle_count(), 1u);
  EXPECT_TRUE(sheet.mesh_S.vertices[2].isApprox(Eigen::Vector3d(0.3, 0.4, 0.3)));
}

TEST(MoveItFiles, TheRequestGivesGroupStartAndGoalAndTheSceneTheOtherJoints) {
  MoveItCase c;
  const Scene scene = load_scene(c.write());
  // The group "arm" is the chain base -> lower: shoulder and elbow.
  ASSERT_EQ(scene.space.planned_joints.size(), 2u);
  EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[0]].name, "shoulder");
  EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[1]].name, "elbow");
  // Start: shoulder from the request's start state, elbow from the scene's robot_state.
  EXPECT_FLOAT_EQ(scene.start[0], -0.5f);
  EXPECT_FLOAT_EQ(scene.start[1], 0.2f);
  EXPECT_FLOAT_EQ(scene.goal[0], 0.7f);
  EXPECT_FLOAT_EQ(scene.goal[1], -0.3f);
  // grip is not planned: robot_state fixes it.
  EXPECT_DOUBLE_EQ(scene.space.fixed_positions[scene.robot.find_joint("grip")], 0.03);
  // The allowed collision matrix: base-lower allowed; lower-table (an object) still checked.
  const int base = scene.robot.find_link("base"), lower = scene.robot.find_link("lower");
  const auto& disabled = scene.robot.disabled_pairs;
  EXPECT_NE(std::find(disabled.begin(), disabled.end(),
                      std::make_pair(std::min(base, lower), std::max(base, lower))),
            disabled.end());
  bool said_table = false, said_nosuch = false;
  for (const std::string& notice : scene.notices) {
    said_table = said_table || notice.find("table (not links of the robot)") != std::string::npos;
    said_nosuch = said_nosuch || notice.find("nosuch") != std::string::npos;
  }
  EXPECT_TRUE(said_table);
  EXPECT_TRUE(said_nosuch);
}

TEST(MoveItFiles, NestedGroupsGiveTheirJointsInTheRobotsOrder) {
  MoveItCase c;
  c.request = R"(group_name: everything
start_state: {joint_state: {name: [shoulder, elbow, grip], position: [0, 0, 0.01]}}
goal_constraints:
  - joint_constraints:
      - {joint_name: grip, position: 0.02}
      - {joint_name: shoulder, position: 0.5}
      - {joint_name: elbow, position: 0.4}
)";
  const Scene scene = load_scene(c.write());
  ASSERT_EQ(scene.space.planned_joints.size(), 3u);
  EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[2]].name, "grip");
  EXPECT_FLOAT_EQ(scene.goal[2], 0.02f);
}

// What the loader must say: "FILE:LINE: KEY: ..." with `says` in it.
void expect_refused(const MoveItCase& c, const std::string& file, int line, const std::string& key,
                    const std::string& says) {
  const std::string scene = c.write();
  try {
    load_scene(scene);
    ADD_FAILURE() << "loaded; expected " << key << ": " << says;
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::string where = c.folder.path() + "/" + file +
                              (line ? ":" + std::to_string(line) : std::string()) + ": " + key +
                              ": ";
    EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\nexpected to start with " << where;
    EXPECT_NE(message.find(says), std::string::npos) << message;
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(MoveItFiles, MistakesAreRefusedNamingFileLineAndKey) {
  const std::string objects = "world.collision_objects";
  {
    MoveItCase c;  // a zero quaternion
    c.planning_scene =
        replaced(kPlanningScene, "orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]",
                 "orientation: [0, 0, 0, 0]");
    expect_refused(c, "world.yaml", 18, objects + "[0].pose.orientation", "zero-length quaternion");
  }
  {
    MoveItCase c;  // far from unit length
    c.planning_scene =
        replaced(kPlanningScene, "orientation: [0, 0, 0.7071067811865476, 0.7071067811865476]",
                 "orientation: [0, 0, 1, 1]");
    expect_refused(c, "world.yaml", 18, objects + "[0].pose.orientation", "not 1");
  }
  {
    MoveItCase c;  // an unknown primitive type
    c.planning_scene = replaced(kPlanningScene, "- type: box", "- type: pyramid");
    expect_refused(c, "world.yaml", 20, objects + "[0].primitives[0].type",
                   "'pyramid' is not a SolidPrimitive type");
  }
  {
    MoveItCase c;  // missing dimensions
    c.planning_scene = replaced(kPlanningScene, "          dimensions: [0.2, 0.3, 0.4]\n", "");
    expect_refused(c, "world.yaml", 20, objects + "[0].primitives[0].dimensions", "missing");
  }
  {
    MoveItCase c;  // a box of two dimensions
    c.planning_scene = replaced(kPlanningScene, "[0.2, 0.3, 0.4]", "[0.2, 0.3]");
    expect_refused(c, "world.yaml", 21, objects + "[0].primitives[0].dimensions",
                   "list of 3 numbers");
  }
  {
    MoveItCase c;  // a negative radius
    c.planning_scene =
        replaced(kPlanningScene, "{type: 2, dimensions: [0.1]}", "{type: 2, dimensions: [-0.1]}");
    expect_refused(c, "world.yaml", 27, objects + "[1].primitives[0].dimensions",
                   "must be positive");
  }
  {
    MoveItCase c;  // a mesh triangle naming a vertex it lacks
    c.planning_scene =
        replaced(kPlanningScene, "vertex_indices: [0, 1, 2]", "vertex_indices: [0, 1, 3]");
    expect_refused(c, "world.yaml", 38, objects + "[3].meshes[0].triangles[0]", "0-based");
  }
  {
    MoveItCase c;  // fewer poses than primitives
    c.planning_scene = replaced(kPlanningScene,
                                "      primitive_poses:\n        - {position: [-0.3, -0.3, 0.3], "
                                "orientation: [0, 0, 0, 1]}\n",
                                "");
    expect_refused(c, "world.yaml", 25, objects + "[1].primitive_poses", "one pose per entry");
  }
  {
    MoveItCase c;  // a misspelt key
    c.planning_scene = replaced(kPlanningScene, "    - id: ball", "    - idd: ball");
    expect_refused(c, "world.yaml", 25, objects + "[1].idd", "unknown key");
  }
  {
    MoveItCase c;  // a frame not resolved
    c.planning_scene = replaced(kPlanningScene, "frame_id: world", "frame_id: camera");
    expect_refused(c, "world.yaml", 15, objects + "[0].header.frame_id", "frame 'camera'");
  }
  {
    MoveItCase c;  // a group the SRDF lacks
    c.request = replaced(kRequest, "group_name: arm", "group_name: legs");
    expect_refused(c, "request.yaml", 1, "group_name",
                   "has no group 'legs'; use one of its groups (arm, hand, everything)");
  }
  {
    MoveItCase c;  // a pose goal
    c.request = std::string(kRequest) + "    position_constraints: [{link_name: lower}]\n";
    expect_refused(c, "request.yaml", 11, "goal_constraints[0].position_constraints",
                   "not a joint goal");
  }
  {
    MoveItCase c;  // a joint of the group left free
    c.request = replaced(kRequest, "      - {joint_name: elbow, position: -0.3}\n", "");
    expect_refused(c, "request.yaml", 0, "goal_constraints[0].joint_constraints",
                   "leaves joint 'elbow'");
  }
  {
    MoveItCase c;  // a goal beyond the joint's limits
    c.request = replaced(kRequest, "position: -0.3", "position: -3");
    expect_refused(c, "request.yaml", 10, "goal_constraints[0].joint_constraints[1].position",
                   "outside its limits [-2, 2]");
  }
  {
    MoveItCase c;  // start: beside a request
    c.scene_extra = "start: {joints: {shoulder: 0, elbow: 0}}\n";
    expect_refused(c, "scene.yaml", 8, "start", "come from moveit.request");
  }
}

// MoveIt's .scene text (RViz's export), in the newer format (an object pose line) and the
// older one (none), read as MoveIt reads it: cylinder "radius length", poses
// "x y z" then "qx qy qz qw", a colour per shape, subframes in the newer format.
TEST(MoveItFiles, SceneTextInBothFormats) {
  {
    MoveItCase c;
    c.folder.write("world.scene", R"(kitchen
* table
0.3 0 0.2
0 0 0.7071067811865476 0.7071067811865476
2
box
0.2 0.3 0.4
0.1 0 0
0 0 0 1
0 0 0 0
mesh
3 1
0.3 0.3 0.3
0.4 0.3 0.3
0.3 0.4 0.3
0 1 2
0 0 0
0 0 0 1
0.5 0.5 0.5 1
1
handle 0 0 0.1 0 0 0 1
.
)");
    c.request = replaced(kRequest, "name: [shoulder]\n    position: [-0.5]",
                         "name: [shoulder, elbow]\n    position: [-0.5, 0.2]");
    const std::string file = c.write();
    c.folder.write("scene.yaml",
                   "name: moveit_arm\nrobot:\n  urdf: arm.urdf\n  srdf: arm.srdf\n"
                   "moveit:\n  scene: world.scene\n  request: request.yaml\n");
    const Scene scene = load_scene(file);
    ASSERT_EQ(scene.obstacles.size(), 2u);
    const Obstacle& box = obstacle(scene, "table[0]");
    EXPECT_EQ(box.shape, ObstacleShape::kBox);
    EXPECT_TRUE(box.X_SO.translation().isApprox(Eigen::Vector3d(0.3, 0.1, 0.2), 1e-12));
    const Obstacle& mesh = obstacle(scene, "table[1]");
    ASSERT_EQ(mesh.mesh_S.triangle_count(), 1u);
    // The mesh turned a quarter about z with the object and moved to (0.3, 0, 0.2).
    EXPECT_TRUE(mesh.mesh_S.vertices[0].isApprox(Eigen::Vector3d(0.0, 0.3, 0.5), 1e-12))
        << mesh.mesh_S.vertices[0].transpose();
  }
  {
    MoveItCase c;
    c.folder.write("world.scene",
                   "old\n* can\n1\ncylinder\n0.1 0.4\n0 -0.3 0.3\n0 0 0 1\n0 0 0 0\n.\n");
    c.request = replaced(kRequest, "name: [shoulder]\n    position: [-0.5]",
                         "name: [shoulder, elbow]\n    position: [-0.5, 0.2]");
    c.write();
    const std::string file =
        c.folder.write("scene.yaml",
                       "name: moveit_arm\nrobot:\n  urdf: arm.urdf\n  srdf: arm.srdf\n"
                       "moveit:\n  scene: world.scene\n  request: request.yaml\n");
    const Scene scene = load_scene(file);
    ASSERT_EQ(scene.obstacles.size(), 1u);
    EXPECT_EQ(scene.obstacles[0].name, "can");
    EXPECT_DOUBLE_EQ(scene.obstacles[0].dimensions.x(), 0.1);  // radius
    EXPECT_DOUBLE_EQ(scene.obstacles[0].dimensions.y(), 0.4);  // length
  }
}

TEST(MoveItFiles, SceneTextMistakesNameTheLine) {
  struct Case {
    const char* text;
    int line;
    const char* key;
    const char* says;
  };
  const Case cases[] = {
      {"s\n* a\n1\npyramid\n1 1 1\n", 4, "object 'a' shape 0", "'pyramid' is not a shape"},
      {"s\n* a\n1\nbox\n0.1 0.1\n", 5, "object 'a' shape 0", "cut short"},
      {"s\n* a\n1\nbox\n0.1 x 0.1\n", 5, "object 'a' shape 0", "found 'x'"},
      {"s\n* a\n1\nsphere\n-1\n0 0 0\n0 0 0 1\n0 0 0 0\n.\n", 4, "object 'a' shape 0",
       "must be positive"},
      {"s\n* a\n1\nsphere\n0.1\n0 0 0\n0 0 0 0\n0 0 0 0\n.\n", 7, "object 'a' shape 0 pose",
       "zero-length quaternion"},
      {"s\n* a\n1\nsphere\n0.1\n0 0 0\n0 0 0 1\n0 0 0 0\n", 8, "end", "closing '.'"},
      {"s\n* a\n1\nmesh\n3 1\n0 0 0\n1 0 0\n0 1 0\n0 1 3\n", 9, "object 'a' shape 0 triangle",
       "0-based"},
      {"s\nx a\n", 2, "object", "expected '* OBJECT_ID'"},
      {"s\n* a\n1\ncone\n0.1 0.2\n", 4, "object 'a' shape 0", "give a cone as a mesh"},
  };
  for (const Case& k : cases) {
    MoveItCase c;
    c.folder.write("world.scene", k.text);
    c.write();
    const std::string file =
        c.folder.write("scene.yaml",
                       "name: moveit_arm\nrobot:\n  urdf: arm.urdf\n  srdf: arm.srdf\n"
                       "moveit:\n  scene: world.scene\n  request: request.yaml\n");
    try {
      load_scene(file);
      ADD_FAILURE() << "loaded: " << k.text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      const std::string where =
          c.folder.path() + "/world.scene:" + std::to_string(k.line) + ": " + k.key + ": ";
      EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\nexpected " << where;
      EXPECT_NE(message.find(k.says), std::string::npos) << message;
    }
  }
}

// The first problem of every MotionBenchMaker Panda scenario: its start, goal and first
// object against the values in its files (read by hand), every object there.
TEST(MoveItFiles, MotionBenchMakersFirstProblemOfEveryScenario) {
  const std::string data = testing::shared_data();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)";
  const std::string panda = data + "/motionbenchmaker/panda";
  struct Problem {
    const char* scenario;
    std::size_t objects;
    const char* first;
    ObstacleShape shape;
    Eigen::Vector3d position;
    Eigen::Quaterniond orientation;  // w, x, y, z
    std::vector<float> start, goal;
  };
  const std::vector<float> ready = {0, -0.785f, 0, -2.356f, 0, 1.571f, 0.785f};
  const Problem problems[] = {
      {"bookshelf_small",
       7,
       "Can1",
       ObstacleShape::kCylinder,
       {0.2477726773362563, -1.073506349336661, 0.2979866994332424},
       {0.8521017127688338, 0, 0, -0.5233762232815127},
       ready,
       {1.48904932702624f, -0.1466710603206631f, -2.884974659739898f, -2.17455683759071f,
        2.709922823933047f, 2.353209641613885f, 1.06196398075046f}},
      {"bookshelf_tall",
       15,
       "Can1",
       ObstacleShape::kCylinder,
       {0.4220889726278536, 1.013326674029394, 0.6799999999999999},
       {0.8474983242662829, 0, 0, 0.5307980692936275},
       ready,
       {-2.778332700195202f, -0.7589568281648941f, -2.491888262891716f, -2.135540657583325f,
        2.89729990721644f, 2.024767106445084f, 0.4576113800781441f}},
      {"bookshelf_thin",
       21,
       "Can1",
       ObstacleShape::kCylinder,
       {0.8500652996649785, 0.656977940169887, -0.26},
       {0.9972531602635496, 0, 0, 0.07406844364750122},
       ready,
       {0.876050380636148f, 1.08259059555153f, -0.7252369320967396f, -2.222271907174576f,
        -2.875483399624016f, 1.724932084474935f, 1.390785275564202f}},
      {"box",
       7,
       "Can1",
       ObstacleShape::kCylinder,
       {0.5408380884576693, 0.3580155146897772, -0.3762264457751537},
       {0.9972531602635496, 0, 0, 0.07406844364750122},
       ready,
       {0.4534448383669427f, 1.7628f, 0.1941262264518609f, -0.8667848896139277f,
        -0.3798524112731043f, 2.606927984171601f, -0.1898611792470702f}},
      {"cage",
       8,
       "Cube1",
       ObstacleShape::kBox,
       {0.7444402652852363, -0.1411031622851692, 0.2599367587044526},
       {0.999201106504633, 0, 0, -0.03996434360673529},
       ready,
       {-0.5545218656333819f, 0.4202507223196937f, 0.3286814744796756f, -1.977673518937082f,
        2.8973f, 2.341192360593145f, -2.31787312121598f}},
      {"table_pick",
       12,
       "Can1",
       ObstacleShape::kCylinder,
       {0.308907161037877, 0.8398608492910964, 0.2984669621486253},
       {0.8679342998251661, 0, 0, 0.4966790222940755},
       ready,
       {-1.451140183264752f, -0.9510103288438848f, 2.419034489081648f, -1.139058262758865f,
        -2.647403722074262f, 2.824576369312635f, 0.8869533207576928f}},
      {"table_under_pick",
       12,
       "Can1",
       ObstacleShape::kCylinder,
       {0.5268272843683661, 0.7400179940187637, 0.3616124775462733},
       {0.8792935401845499, 0, 0, 0.4762802433333986},
       {0.259545223334237f, 1.7628f, 1.047662098941416f, -1.227360797299392f, 2.419685742648223f,
        2.383341301579456f, 0.08066880220773931f},
       {-2.591578857793795f, -1.707376195315788f, -1.027817405770607f, -1.040064414915441f,
        0.2026897400013632f, 3.743816877074496f, 1.642189515655314f}},
  };
  for (const Problem& p : problems) {
    SCOPED_TRACE(p.scenario);
    const ScratchFolder folder;
    const std::string dir = panda + "/problems/" + p.scenario + "_panda";
    const std::string file = folder.write(
        "scene.yaml", "robot:\n  urdf: " + panda + "/robot/panda.urdf\n  srdf: " + panda +
                          "/robot/panda.srdf\n  packages: {meshes: " + panda +
                          "/robot/meshes}\nmoveit:\n  scene: " + dir +
                          "/scene0001.yaml\n  request: " + dir + "/request0001.yaml\n");
    const Scene scene = load_scene(file);
    // Objects out of the arm's reach are dropped at load (docs/scenes.md): at most the file's.
    EXPECT_LE(scene.obstacles.size(), p.objects);
    EXPECT_GE(scene.obstacles.size(), p.objects / 2);
    ASSERT_EQ(scene.space.planned_joints.size(), 7u);
    for (int i = 0; i < 7; ++i) {
      EXPECT_EQ(scene.robot.joints[scene.space.planned_joints[i]].name,
                "panda_joint" + std::to_string(i + 1));
      EXPECT_FLOAT_EQ(scene.start[i], p.start[i]) << i;
      EXPECT_FLOAT_EQ(scene.goal[i], p.goal[i]) << i;
    }
    const Obstacle& first = obstacle(scene, p.first);
    EXPECT_EQ(first.shape, p.shape);
    EXPECT_TRUE(first.X_SO.translation().isApprox(p.position, 1e-12))
        << first.X_SO.translation().transpose();
    EXPECT_LT(Eigen::Quaterniond(first.X_SO.linear()).angularDistance(p.orientation.normalized()),
              1e-9);
  }
}

}  // namespace
}  // namespace gplanner
