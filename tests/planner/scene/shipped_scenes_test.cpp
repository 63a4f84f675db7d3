// Every scene in scenes/ is a real planning problem: it loads, start and goal are free
// with the clearance their generator promises, the straight line between them collides
// over a stretch, the robot's zero pose is free of self-collision, and the narrowest
// passage is stated. (That a path exists is tests/apps/gplan_plan_test's.)

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <utility>
#include <vector>

#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, IsARealPlanningProblem) {
  const std::string file = testing::project_root() + "/scenes/" + GetParam();
  const Scene scene = load_scene(file);
  EXPECT_FALSE(scene.narrowest_passage.empty()) << "state the narrowest passage";
  EXPECT_GT(scene.robot.triangle_count(), 1000u);
  EXPECT_GT(scene.obstacle_triangle_count(), 100u);
  FclChecker checker(scene);
  EXPECT_NO_THROW(check_start_and_goal(scene, &checker));
  const double t = first_collision_on_straight_line(scene, &checker);
  EXPECT_GT(t, 0) << "the straight line from start to goal must collide";
  std::cout << scene.name << ": " << scene.robot.triangle_count() << " robot triangles, "
            << scene.obstacle_triangle_count() << " obstacle triangles, " << scene.space.dof()
            << " DOF; straight line collides at " << 100 * t << "%\n";
}

// What robots/*/generate.py promises at start and goal: the clearance (m) from the
// obstacles and between the checked link pairs; for the PR2, the pairs that the elbow's
// and the wrist's clevis hold a few mm apart at any pose, and the clearance those keep.
struct Clearance {
  double obstacles = 0;
  double self = 0;
  std::vector<std::pair<std::string, std::string>> joint_gaps;
  double joint_gap = 0;
};

std::vector<std::pair<std::string, std::string>> pr2_clevis_pairs() {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string side : {"l_", "r_"}) {
    for (const auto& [a, b] : {std::pair{"forearm_link", "wrist_roll_link"},
                               std::pair{"forearm_link", "gripper_palm_link"},
                               std::pair{"forearm_roll_link", "upper_arm_link"},
                               std::pair{"forearm_link", "upper_arm_link"}}) {
      pairs.emplace_back(side + a, side + b);
    }
  }
  return pairs;
}

const std::map<std::string, Clearance>& promised_clearances() {
  static const std::map<std::string, Clearance> promised = {
      {"piano", {0.02, 0, {}, 0}},
      {"piano_detailed", {0.02, 0, {}, 0}},
      {"large_piano", {0.02, 0, {}, 0}},
      {"helicopter", {0.05, 0, {}, 0}},
      {"humanoid", {0.02, 0.02, {}, 0}},
      {"pr2_reach", {0.02, 0.02, pr2_clevis_pairs(), 0.005}},
      {"pr2_base_arm", {0.02, 0.02, pr2_clevis_pairs(), 0.005}},
  };
  return promised;
}

// FCL's least distance at q: from the robot to the obstacles (self = false: no link pair
// checked), or between the robot's checked link pairs less `unchecked` (self = true: no
// obstacles). Infinite when there is nothing to measure.
double least_distance(Scene scene, const std::vector<float>& q, bool self,
                      const std::vector<std::pair<std::string, std::string>>& unchecked = {}) {
  RobotModel& robot = scene.robot;
  const int links = static_cast<int>(robot.links.size());
  if (self) {
    scene.obstacles.clear();
  } else {
    for (int a = 0; a < links; ++a) {
      for (int b = a + 1; b < links; ++b) robot.disabled_pairs.emplace_back(a, b);
    }
  }
  for (const auto& [first, second] : unchecked) {
    const int a = robot.find_link(first), b = robot.find_link(second);
    EXPECT_TRUE(a >= 0 && b >= 0) << first << " / " << second << ": no such link";
    robot.disabled_pairs.emplace_back(std::min(a, b), std::max(a, b));
  }
  FclChecker checker(scene);
  double distance = 0;
  checker.distance(q.data(), 1, &distance);
  return distance;
}

TEST_P(ShippedScene, StartAndGoalKeepThePromisedClearance) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const auto promised = promised_clearances().find(testing::scene_test_name(GetParam()));
  ASSERT_NE(promised, promised_clearances().end())
      << "state the clearance the scene's generator promises at start and goal";
  const Clearance& c = promised->second;
  const auto ends = {std::pair{"start", &scene.start}, std::pair{"goal", &scene.goal}};
  for (const auto& [which, q] : ends) {
    const double obstacles = least_distance(scene, *q, false);
    const double self = least_distance(scene, *q, true, c.joint_gaps);
    EXPECT_GE(obstacles, c.obstacles) << which << ": from the obstacles";
    EXPECT_GE(self, c.self) << which << ": between the checked link pairs";
    if (!c.joint_gaps.empty()) {
      EXPECT_GE(least_distance(scene, *q, true), c.joint_gap) << which << ": across the clevises";
    }
    std::cout << scene.name << " " << which << ": " << 100 * obstacles << " cm from the obstacles, "
              << 100 * self << " cm between links\n";
  }
}

// The robot alone at the all-zero joint configuration touches itself nowhere but in the
// pairs the SRDF disables (humanoid: generate.py disables the pairs within 1 cm there;
// PR2: its "Default" pairs are those touching there). Every joint of both robots has 0
// within its limits.
TEST_P(ShippedScene, ZeroPoseIsFreeOfSelfCollision) {
  Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  if (scene.robot.links.size() < 2) GTEST_SKIP() << "a rigid robot";
  scene.obstacles.clear();
  std::fill(scene.space.fixed_positions.begin(), scene.space.fixed_positions.end(), 0.0);
  std::vector<float> q = scene.start;  // the base where the start puts it
  std::fill(q.begin() + scene.space.base_width(), q.end(), 0.0f);
  FclChecker checker(scene);
  EXPECT_FALSE(checker.in_collision(q.data()));
}

// The straight line does not merely graze an obstacle: it collides over at least 5% of
// the way (FCL finds the shipped scenes' lines colliding over 31% (humanoid) to 68%
// (pr2_base_arm) of the way).
TEST_P(ShippedScene, StraightLineIsBlockedOverAStretch) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const std::size_t width = scene.space.width(), samples = 1001;
  std::vector<float> line(samples * width);
  for (std::size_t i = 0; i < samples; ++i) {
    scene.space.interpolate(scene.start.data(), scene.goal.data(),
                            static_cast<double>(i) / (samples - 1), &line[i * width]);
  }
  std::vector<std::uint8_t> verdicts(samples);
  FclChecker checker(scene);
  checker.check(line.data(), samples, verdicts.data());
  const double blocked =
      static_cast<double>(std::count(verdicts.begin(), verdicts.end(), 1)) / samples;
  EXPECT_GE(blocked, 0.05);
  std::cout << scene.name << ": the straight line collides over " << 100 * blocked
            << "% of the way\n";
}

TEST(ShippedScenes, DefaultSceneExists) {
  const std::vector<std::string> scenes = testing::shipped_scene_files();
  EXPECT_NE(std::find(scenes.begin(), scenes.end(), "piano.yaml"), scenes.end());
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(testing::shipped_scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testing::scene_test_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ShippedScene);

}  // namespace
}  // namespace gplanner
