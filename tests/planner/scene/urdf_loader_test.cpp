// URDF collision geometry that cannot be lost without a word, and adjacency as MoveIt
// has it: links joined through links without collision geometry are adjacent.

#include "gplanner/planner/scene/urdf_loader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

// Two links: 'base', a box, and 'arm', whose collision elements ARM_COLLISION stands for.
const char* const kTwoLinks = R"(<?xml version="1.0"?>
<robot name="two">
  <link name="base">
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
  </link>
  <link name="arm">
    <visual><geometry><box size="0.1 0.1 0.5"/></geometry></visual>
ARM_COLLISION
  </link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
</robot>
)";

// A collision urdfdom and we both read, placed before each broken one: urdfdom drops it
// too when it cannot read the next, so that 'arm' would have no geometry at all.
const char* const kGoodCollision =
    "    <collision><origin xyz=\"0 0 0.25\"/><geometry><box size=\"0.1 0.1 0.5\"/></geometry>"
    "</collision>\n";

std::string two_links(const std::string& arm_collision) {
  std::string text = kTwoLinks;
  const std::string slot = "ARM_COLLISION";
  return text.replace(text.find(slot), slot.size(), arm_collision);
}

// 1-based number of the last line of `text` holding `needle` (the element at fault
// comes after the good ones in every case here).
int line_of(const std::string& text, const std::string& needle) {
  std::istringstream lines(text);
  std::string line;
  int found = 0;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.find(needle) != std::string::npos) found = number;
  }
  if (found == 0) ADD_FAILURE() << "no line holds '" << needle << "'";
  return found;
}

class UrdfLoader : public ::testing::Test {
 protected:
  // Loads `text` as robot.urdf; the error's message when it fails, else "".
  std::string error_of(const std::string& text, SourceLocation* where = nullptr) {
    path_ = scratch_.write("robot.urdf", text);
    try {
      load_urdf(path_, {}, {"scene.yaml", 3, "robot.urdf"}, &notices_);
    } catch (const InputError& e) {
      if (where) *where = e.where();
      return e.what();
    }
    return "";
  }

  // Expects `text` to fail at the line holding `needle` with `key`, the message in the
  // project's form (FILE:LINE: KEY: what is wrong; what to change) and saying `also`.
  void expect_error(const std::string& text, const std::string& needle, const std::string& key,
                    const std::vector<std::string>& also) {
    SourceLocation where;
    const std::string message = error_of(text, &where);
    ASSERT_FALSE(message.empty()) << "loaded without an error:\n" << text;
    EXPECT_EQ(where.file, path_) << message;
    EXPECT_EQ(where.line, line_of(text, needle)) << message;
    EXPECT_EQ(where.key, key) << message;
    const std::string prefix =
        path_ + ":" + std::to_string(line_of(text, needle)) + ": " + key + ": ";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    EXPECT_NE(message.find("; ", prefix.size()), std::string::npos)
        << "says nothing to change: " << message;
    for (const std::string& part : also) {
      EXPECT_NE(message.find(part), std::string::npos)
          << "does not say '" << part << "': " << message;
    }
  }

  testing::ScratchFolder scratch_;
  std::string path_;
  std::vector<std::string> notices_;
};

TEST_F(UrdfLoader, ReadsGoodCollisions) {
  scratch_.write("part.obj",
                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                 "f 2 3 4\n");
  EXPECT_EQ(error_of(two_links(std::string(kGoodCollision) +
                               "    <collision><origin xyz=\"+0 .5 1e-3\" rpy=\" 0  0 1 \"/>"
                               "<geometry><mesh filename=\"part.obj\" scale=\"1 -2 1\"/>"
                               "</geometry></collision>\n")),
            "");
  EXPECT_TRUE(notices_.empty());
}

// Each broken <collision> of 'arm' (after a good one): an error naming the file, the
// line of the element at fault and the link. urdfdom 3 logs these and drops every
// collision of the link (or, for the zero and negative sizes and the second shape,
// reads them as they are), and 'arm' became invisible.
TEST_F(UrdfLoader, UnreadableCollisionIsAnErrorNamingFileLineAndLink) {
  struct Case {
    std::string collision;
    std::string needle;  // on the line the error must name
    std::vector<std::string> says;
  };
  const std::string box = "<geometry><box size=\"0.1 0.1 0.5\"/></geometry>";
  const std::vector<Case> cases = {
      {"<origin xyz=\"0 0 abc\"/>" + box, "abc", {"xyz=\"0 0 abc\"", "three finite numbers"}},
      {"<origin xyz=\"0 0 nan\"/>" + box, "nan", {"xyz=\"0 0 nan\"", "three finite numbers"}},
      {"<origin xyz=\"0 0 1e999\"/>" + box, "1e999", {"three finite numbers"}},
      {"<origin xyz=\"0 0\"/>" + box, "xyz=\"0 0\"", {"three finite numbers", "metres"}},
      {"<origin rpy=\"0 0 0.5 0\"/>" + box, "rpy", {"rpy=\"0 0 0.5 0\"", "radians"}},
      {"<geometry>\n<mesh filename=\"part.obj\" scale=\"1 1\"/>\n</geometry>",
       "scale",
       {"scale=\"1 1\"", "three finite non-zero numbers"}},
      {"<geometry>\n<mesh filename=\"part.obj\" scale=\"1 1 abc\"/>\n</geometry>",
       "scale",
       {"scale=\"1 1 abc\""}},
      {"<geometry>\n<mesh filename=\"part.obj\" scale=\"1 0 1\"/>\n</geometry>",
       "scale",
       {"scale=\"1 0 1\"", "non-zero"}},
      {"<geometry>\n<mesh/>\n</geometry>", "<mesh/>", {"no filename"}},
      {"<geometry>\n<box size=\"0.1 0.1\"/>\n</geometry>", "size", {"size=\"0.1 0.1\""}},
      {"<geometry>\n<box size=\"0 0.1 0.5\"/>\n</geometry>", "size", {"positive"}},
      {"<geometry>\n<box size=\"-0.1 0.1 0.5\"/>\n</geometry>", "size", {"size=\"-0.1"}},
      {"<geometry>\n<box/>\n</geometry>", "<box/>", {"no size attribute"}},
      {"<geometry>\n<sphere radius=\"-0.1\"/>\n</geometry>", "radius", {"radius=\"-0.1\""}},
      {"<geometry>\n<sphere radius=\"NaN\"/>\n</geometry>", "radius", {"positive finite"}},
      {"<geometry>\n<cylinder radius=\"0.05\"/>\n</geometry>", "cylinder", {"no length"}},
      {"<geometry>\n<cylinder radius=\"0.05\" length=\"0\"/>\n</geometry>",
       "cylinder",
       {"length=\"0\""}},
      {"<geometry>\n<capsule radius=\"0.05\" length=\"0.5\"/>\n</geometry>",
       "capsule",
       {"<capsule> is not a shape", "<box>, <cylinder>, <sphere> or <mesh>"}},
      {"<geometry/>", "<geometry/>", {"empty"}},
      {"<origin xyz=\"0 0 0.1\"/>", "<collision>", {"no <geometry>"}},
      {"<geometry><box size=\"0.1 0.1 0.5\"/>\n<sphere radius=\"0.2\"/></geometry>",
       "sphere",
       {"more than one shape", "a <collision> of its own"}},
  };
  scratch_.write("part.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.collision);
    // The broken collision on lines of its own, so that the line named is its element's.
    const std::string text = two_links(std::string(kGoodCollision) + "    <collision>\n" +
                                       c.collision + "\n" + "    </collision>");
    expect_error(text, c.needle, "link 'arm' collision", c.says);
  }
}

// urdfdom drops a link's collisions when it cannot read its <visual> or <inertial>
// either: an error naming the element urdfdom names.
TEST_F(UrdfLoader, CollisionsDroppedForAnotherElementAreAnError) {
  std::string text = two_links(kGoodCollision);
  const std::string visual = "<visual><geometry><box size=\"0.1 0.1 0.5\"/></geometry></visual>";
  text.replace(text.find(visual), visual.size(),
               "<visual><origin xyz=\"0 0 oops\"/><geometry><box size=\"0.1 0.1 0.5\"/>"
               "</geometry></visual>");
  // Numbers are read before urdfdom (which would drop the link's collisions for it):
  // the error names the element.
  expect_error(text, "oops", "link 'arm' <origin xyz>", {"'oops' is not a finite number"});

  text =
      two_links(std::string("    <inertial><mass value=\"heavy\"/></inertial>\n") + kGoodCollision);
  expect_error(text, "heavy", "link 'arm' <mass value>", {"'heavy' is not a finite number"});
}

TEST_F(UrdfLoader, RobotWithoutCollisionGeometryIsAnError) {
  std::string text = two_links("");
  const std::string base_collision =
      "<collision><geometry><box size=\"0.2 0.2 0.2\"/></geometry></collision>";
  text.replace(text.find(base_collision), base_collision.size(), "");
  expect_error(text, "<robot name=\"two\">", "robot 'two'",
               {"no link has collision geometry", "add a <collision>"});
}

// A misspelt element is skipped, as urdfdom skips it, but not without a word.
TEST_F(UrdfLoader, ElementsAUrdfDoesNotDefineAreNoticed) {
  const std::string text = two_links(
      "    <colision><geometry><box size=\"0.1 0.1 0.5\"/></geometry></colision>\n"
      "    <collision><orgin xyz=\"0 0 0.25\"/><geometry><box size=\"0.1 0.1 0.5\"/>"
      "</geometry></collision>\n");
  ASSERT_EQ(error_of(text), "");
  ASSERT_EQ(notices_.size(), 2u);
  EXPECT_EQ(notices_[0], path_ + ":" + std::to_string(line_of(text, "<colision>")) +
                             ": link 'arm': <colision> is not part of a URDF link; skipped");
  EXPECT_EQ(notices_[1], path_ + ":" + std::to_string(line_of(text, "<orgin")) +
                             ": link 'arm' collision: <orgin> is not part of a URDF collision; "
                             "skipped");
}

// Mesh files that hold no triangle, or whose own transforms flatten them, are errors
// naming the URDF line.
TEST_F(UrdfLoader, CollisionMeshesWithoutTrianglesAreErrors) {
  scratch_.write("empty.stl", std::string(80, '\0') + std::string(4, '\0'));
  scratch_.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  scratch_.write("flat.dae",
                 R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><up_axis>Z_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array><technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles></mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n" name="n"><scale>1 0 1</scale><instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene></COLLADA>
)");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"empty.stl", "cannot be read"}, {"points.obj", "no triangles"}, {"flat.dae", "flattened"}};
  for (const auto& [file, says] : cases) {
    const std::string text =
        two_links(std::string(kGoodCollision) + "    <collision><geometry>\n<mesh filename=\"" +
                  file + "\"/>\n</geometry></collision>");
    expect_error(text, "<mesh filename", "link 'arm' collision", {file, says});
  }
}

// A tree with geometry-less links in three places, and the pairs MoveIt's Setup
// Assistant calls adjacent:
//   base -> mount* -> arm -> wrist* -> flange* -> hand -> finger_l, finger_r
//                                   -> camera
//   base -> hub* -> wheel_l, wheel_r                      (* no collision geometry)
// At the zero pose, hand overlaps arm (through wrist and flange), camera overlaps hand
// and arm (through wrist), the wheels overlap each other and the base (through hub):
// all adjacent. The fingers (a pair of siblings under hand, which has geometry) are
// not: closed (finger_l = 0) they overlap, open (0.08) they are apart.
const char* const kTreeUrdf = R"(<?xml version="1.0"?>
<robot name="tree">
  <link name="base"><collision><geometry><box size="0.4 0.4 0.1"/></geometry></collision></link>
  <link name="mount"/>
  <link name="arm"><collision><origin xyz="0 0 0.3"/><geometry><box size="0.1 0.1 0.6"/></geometry></collision></link>
  <link name="wrist"/>
  <link name="flange"/>
  <link name="hand"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="camera"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="finger_l"><collision><geometry><box size="0.05 0.05 0.1"/></geometry></collision></link>
  <link name="finger_r"><collision><geometry><box size="0.05 0.05 0.1"/></geometry></collision></link>
  <link name="hub"/>
  <link name="wheel_l"><collision><origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.1" length="0.1"/></geometry></collision></link>
  <link name="wheel_r"><collision><origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.1" length="0.1"/></geometry></collision></link>
  <joint name="to_mount" type="fixed"><parent link="base"/><child link="mount"/><origin xyz="0 0 0.05"/></joint>
  <joint name="turn" type="revolute"><parent link="mount"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="bend" type="revolute"><parent link="arm"/><child link="wrist"/><origin xyz="0 0 0.6"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="to_flange" type="fixed"><parent link="wrist"/><child link="flange"/></joint>
  <joint name="to_hand" type="fixed"><parent link="flange"/><child link="hand"/></joint>
  <joint name="to_camera" type="fixed"><parent link="wrist"/><child link="camera"/><origin xyz="0.1 0 0"/></joint>
  <joint name="finger_l" type="prismatic"><parent link="hand"/><child link="finger_l"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="0" upper="0.1" effort="1" velocity="1"/></joint>
  <joint name="finger_r" type="prismatic"><parent link="hand"/><child link="finger_r"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/><limit lower="-0.1" upper="0" effort="1" velocity="1"/>
    <mimic joint="finger_l" multiplier="-1"/></joint>
  <joint name="to_hub" type="fixed"><parent link="base"/><child link="hub"/><origin xyz="0 0 -0.1"/></joint>
  <joint name="wheel_l" type="continuous"><parent link="hub"/><child link="wheel_l"/><origin xyz="0 0.04 0"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="wheel_r" type="continuous"><parent link="hub"/><child link="wheel_r"/><origin xyz="0 -0.04 0"/>
    <axis xyz="0 1 0"/></joint>
</robot>
)";

using NamePair = std::pair<std::string, std::string>;

// The pairs among links with geometry, by name, each sorted.
std::set<NamePair> named_pairs_with_geometry(const RobotModel& robot,
                                             const std::vector<std::pair<int, int>>& pairs) {
  std::set<NamePair> named;
  for (const auto& [a, b] : pairs) {
    if (robot.links[a].collision.empty() || robot.links[b].collision.empty()) continue;
    named.emplace(std::min(robot.links[a].name, robot.links[b].name),
                  std::max(robot.links[a].name, robot.links[b].name));
  }
  return named;
}

// A chain of `links` box links joined by revolute joints.
std::string chain_urdf(int links) {
  std::string text = "<robot name=\"chain\">\n";
  for (int i = 0; i < links; ++i) {
    text += "<link name=\"l" + std::to_string(i) +
            "\"><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n";
  }
  for (int i = 1; i < links; ++i) {
    text += "<joint name=\"j" + std::to_string(i) + "\" type=\"fixed\"><parent link=\"l" +
            std::to_string(i - 1) + "\"/><child link=\"l" + std::to_string(i) + "\"/></joint>\n";
  }
  return text + "</robot>\n";
}

TEST_F(UrdfLoader, RobotsWithTooManyLinksAreRefusedAtOnce) {
  expect_error(chain_urdf(10000), "<robot", "robot",
               {"has 10000 links, more than the 1000 a robot may have"});
  EXPECT_EQ(error_of(chain_urdf(300)), "");
}

// As MoveIt loads them (issue 31): a mimic that drives its joint beyond the joint's own
// limits loads, the joint following the rule there, with a notice naming the joint and
// the range; one that drives it to infinity stays an error.
TEST_F(UrdfLoader, MimicJointsDrivenBeyondTheirLimitsLoadWithANotice) {
  const std::string urdf = R"(<robot name="gripper">
  <link name="palm"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="left"><collision><geometry><box size="0.01 0.01 0.1"/></geometry></collision></link>
  <link name="right"><collision><geometry><box size="0.01 0.01 0.1"/></geometry></collision></link>
  <joint name="open" type="prismatic"><parent link="palm"/><child link="left"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/></joint>
  <joint name="follow" type="prismatic"><parent link="palm"/><child link="right"/>
    <axis xyz="-1 0 0"/><limit lower="0" upper="0.04" effort="1" velocity="1"/>
    <mimic joint="open" multiplier="MULTIPLIER" offset="0"/></joint>
</robot>
)";
  auto with = [&](const std::string& multiplier) {
    std::string text = urdf;
    text.replace(text.find("MULTIPLIER"), 10, multiplier);
    return text;
  };
  EXPECT_EQ(error_of(with("1")), "");
  EXPECT_TRUE(notices_.empty());
  for (const auto& [multiplier, range] :
       {std::pair<std::string, std::string>{"3", "[0, 0.12]"}, {"-1", "[-0.04, 0]"}}) {
    notices_.clear();
    const std::string text = with(multiplier);
    EXPECT_EQ(error_of(text), "") << multiplier;
    ASSERT_EQ(notices_.size(), 1u) << multiplier;
    const std::string prefix = path_ + ":" +
                               std::to_string(line_of(text, "<joint name=\"follow\"")) +
                               ": joint 'follow' mimic: ";
    EXPECT_EQ(notices_[0].rfind(prefix, 0), 0u) << notices_[0];
    EXPECT_NE(notices_[0].find("drive it over " + range), std::string::npos) << notices_[0];
    EXPECT_NE(notices_[0].find("beyond its own limits [0, 0.04]"), std::string::npos)
        << notices_[0];
  }
  // The follower follows the rule beyond its limits.
  const RobotModel robot = load_urdf(scratch_.write("three.urdf", with("3")), {}, {"t", 0, ""});
  const Joint& follow = robot.joints[robot.find_joint("follow")];
  EXPECT_EQ(follow.mimic_joint, robot.find_joint("open"));
  EXPECT_DOUBLE_EQ(follow.mimic_multiplier, 3);
  std::string infinite = with("1e308");
  infinite.replace(infinite.find("offset=\"0\""), 10, "offset=\"1.79e308\"");
  expect_error(infinite, "<joint name=\"follow\"", "joint 'follow' mimic",
               {"beyond any finite value"});
}

// As MoveIt and urdfdom load them: a <mimic> on a fixed joint drives nothing and is
// ignored, with a notice (MotionBenchMaker's Panda puts one on its fixed finger).
TEST_F(UrdfLoader, AMimicOnAFixedJointIsIgnoredWithANotice) {
  const std::string text = R"(<robot name="hand">
  <link name="palm"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="left"><collision><geometry><box size="0.01 0.01 0.1"/></geometry></collision></link>
  <link name="right"><collision><geometry><box size="0.01 0.01 0.1"/></geometry></collision></link>
  <joint name="finger1" type="fixed"><parent link="palm"/><child link="left"/>
    <origin xyz="0 0.05 0"/></joint>
  <joint name="finger2" type="fixed"><parent link="palm"/><child link="right"/>
    <origin xyz="0 -0.05 0"/>
    <mimic joint="finger1"/></joint>
</robot>
)";
  EXPECT_EQ(error_of(text), "");
  ASSERT_EQ(notices_.size(), 1u);
  EXPECT_EQ(notices_[0], path_ + ":" + std::to_string(line_of(text, "<joint name=\"finger2\"")) +
                             ": joint 'finger2' mimic: a <mimic> on a fixed joint drives "
                             "nothing; ignored");
  const RobotModel robot = load_urdf(path_, {}, {"t", 0, ""});
  EXPECT_EQ(robot.joints[robot.find_joint("finger2")].mimic_joint, -1);
}

TEST(Adjacency, LinksJoinedThroughLinksWithoutGeometryAreAdjacent) {
  testing::ScratchFolder scratch;
  const RobotModel robot = load_urdf(scratch.write("tree.urdf", kTreeUrdf), {}, {"test", 0, ""});
  const std::set<NamePair> expected = {{"arm", "base"},          // through mount
                                       {"arm", "hand"},          // through wrist and flange
                                       {"arm", "camera"},        // through wrist
                                       {"camera", "hand"},       // through flange and wrist
                                       {"finger_l", "hand"},     // parent and child
                                       {"finger_r", "hand"},     // parent and child
                                       {"base", "wheel_l"},      // through hub
                                       {"base", "wheel_r"},      // through hub
                                       {"wheel_l", "wheel_r"}};  // siblings under hub
  EXPECT_EQ(named_pairs_with_geometry(robot, adjacent_link_pairs(robot)), expected);
  EXPECT_EQ(robot.disabled_pairs, adjacent_link_pairs(robot));
  // Every parent and child stays a pair, geometry or not.
  for (const Joint& joint : robot.joints) {
    const std::pair<int, int> pair(std::min(joint.parent_link, joint.child_link),
                                   std::max(joint.parent_link, joint.child_link));
    EXPECT_EQ(std::count(robot.disabled_pairs.begin(), robot.disabled_pairs.end(), pair), 1)
        << joint.name;
  }
  // 8 links with geometry, 28 pairs, 9 adjacent: 19 checked, the fingers among them.
  const std::vector<std::pair<int, int>> checked = robot.checked_pairs();
  EXPECT_EQ(checked.size(), 19u);
  EXPECT_EQ(named_pairs_with_geometry(robot, checked).count({"finger_l", "finger_r"}), 1u);
  EXPECT_EQ(named_pairs_with_geometry(robot, checked).count({"base", "hand"}), 1u);
}

// The same tree as a scene: the zero pose, whose adjacent links overlap, is free on
// every CPU backend with the fingers open (0.08), and collides with them closed.
TEST(Adjacency, OverlappingAdjacentLinksDoNotCollide) {
  testing::ScratchFolder scratch;
  scratch.write("tree.urdf", kTreeUrdf);
  const Scene scene = load_scene(scratch.write("tree.yaml", R"(name: tree
robot: {urdf: tree.urdf, planned_joints: [finger_l]}
obstacles:
  - box: [0.1, 0.1, 0.1]
    pose: {xyz: [0.5, 0, 0.2]}
start: {joints: {finger_l: 0.08}}
goal: {joints: {finger_l: 0.09}}
)"));
  for (const char* backend : {"fcl", "cpu"}) {
    SCOPED_TRACE(backend);
    const std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
    const float open = 0.08f, closed = 0.0f;
    EXPECT_FALSE(checker->in_collision(&open));
    EXPECT_TRUE(checker->in_collision(&closed));
  }
}

}  // namespace
}  // namespace gplanner
