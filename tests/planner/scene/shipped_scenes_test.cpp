// Every scene in scenes/ is a real planning problem: it loads, start and goal are free,
// the straight line between them collides, and the narrowest passage is stated.

#include <gtest/gtest.h>

#include <filesystem>

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
