// The path file gives back the path it was given: the configurations, the root's pose
// and the joints by name.

#include "gplanner/planner/output/path_file.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <vector>

#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

TEST(PathFile, RoundTripsTheWaypoints) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  const int width = scene.space.width();
  PlanResult result;
  result.solved = true;
  result.path = testing::sample_configurations(scene, 5, 7);
  result.length = 1.25;
  testing::ScratchFolder scratch;
  const std::string file = scratch.path() + "/path.yaml";
  write_path_file(file, scene, result, "lazyprm", "cpu");

  const YAML::Node root = YAML::LoadFile(file);
  EXPECT_EQ(root["planner"].as<std::string>(), "lazyprm");
  EXPECT_EQ(root["backend"].as<std::string>(), "cpu");
  EXPECT_DOUBLE_EQ(root["length"].as<double>(), 1.25);
  ASSERT_EQ(root["entries"].size(), static_cast<std::size_t>(width));
  const YAML::Node waypoints = root["waypoints"];
  ASSERT_EQ(waypoints.size(), 5u);
  std::vector<double> file_values(width);
  for (std::size_t w = 0; w < waypoints.size(); ++w) {
    const float* q = &result.path[w * width];
    scene.space.to_file_values(q, file_values.data());
    const YAML::Node row = waypoints[w]["configuration"];
    ASSERT_EQ(row.size(), static_cast<std::size_t>(width));
    for (int i = 0; i < width; ++i)
      EXPECT_NEAR(row[i].as<double>(), file_values[i], 1e-6 * (1 + std::fabs(file_values[i])))
          << "waypoint " << w << ", entry " << root["entries"][i].as<std::string>();
    const Eigen::Vector3d t = (scene.X_WS() * scene.space.base_pose(q)).translation();
    const YAML::Node position = waypoints[w]["base"]["position"];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(position[k].as<double>(), t[k], 1e-6);
    EXPECT_TRUE(waypoints[w]["joints"].IsMap()) << "the PR2's joints by name";
  }
}

// Joint names and a scene file name that would break unquoted YAML read back as given.
TEST(PathFile, HostileNamesReadBackAsGiven) {
  Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  const std::vector<std::string> hostile = {"a: b", "#x",     "\"", "\\",   "new\nline",
                                            "- z",  "*alias", "{",  "true", "\x1b[2J"};
  std::vector<std::string> names;
  int renamed = 0;
  for (Joint& joint : scene.robot.joints) {
    if (!joint.is_single_dof()) continue;
    joint.name = hostile[renamed % hostile.size()] + "_" + std::to_string(renamed);
    // The first of them without a suffix, as hostile as given.
    if (renamed < static_cast<int>(hostile.size())) joint.name = hostile[renamed];
    ++renamed;
  }
  ASSERT_GE(renamed, static_cast<int>(hostile.size()));
  scene.file = "scene: \"odd\"\n# name.yaml";
  const int width = scene.space.width();
  PlanResult result;
  result.solved = true;
  result.path = testing::sample_configurations(scene, 2, 3);
  testing::ScratchFolder scratch;
  const std::string file = scratch.path() + "/path.yaml";
  write_path_file(file, scene, result, "lazyprm", "cpu");

  const YAML::Node root = YAML::LoadFile(file);
  EXPECT_EQ(root["scene"].as<std::string>(), scene.file);
  ASSERT_EQ(root["entries"].size(), static_cast<std::size_t>(width));
  for (int i = 0; i < width; ++i)
    EXPECT_EQ(root["entries"][i].as<std::string>(), scene.space.entry_name(scene.robot, i));
  const YAML::Node joints = root["waypoints"][0]["joints"];
  ASSERT_TRUE(joints.IsMap());
  EXPECT_EQ(joints.size(), static_cast<std::size_t>(renamed));
  for (const Joint& joint : scene.robot.joints) {
    if (!joint.is_single_dof()) continue;
    EXPECT_TRUE(joints[joint.name].IsScalar()) << "joint '" << joint.name << "' read back";
  }
}

}  // namespace
}  // namespace gplanner
