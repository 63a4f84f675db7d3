// The cpu backend (the collision core on host threads) against FCL on every shipped
// scene: never a missed collision, extra collisions only within the tolerance band.

#include "gplanner/planner/cpu_checker.h"

#include <gtest/gtest.h>

#include "gplanner/planner/checker_comparison.h"
#include "gplanner/planner/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

class CpuAgreesWithFcl : public ::testing::TestWithParam<std::string> {};

TEST_P(CpuAgreesWithFcl, WithinTheToleranceBand) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + GetParam());
  const std::size_t n = 3000, width = scene.space.width();
  const std::vector<float> q = testing::sample_configurations(scene, n, 17);
  CpuChecker cpu(scene);
  FclChecker fcl(scene);
  std::vector<std::uint8_t> a(n), b(n);
  cpu.check(q.data(), n, a.data());
  fcl.check(q.data(), n, b.data());
  const CheckerComparison c =
      compare_verdicts(q.data(), n, width, a.data(), b.data(), &fcl, tolerance_delta(scene));
  EXPECT_EQ(c.missed_collisions, 0u);
  EXPECT_EQ(c.extra_outside_band, 0u) << "largest distance " << c.largest_extra_distance;
  EXPECT_GT(cpu.bv_tests(), 0u);
  std::size_t hits = 0;
  for (std::uint8_t v : b) hits += v;
  EXPECT_GT(hits, 0u);
  EXPECT_LT(hits, n);
  std::cout << GetParam() << ": " << c.disagreements << " disagreements of " << n << ", "
            << c.extra_within_band << " within the band; " << cpu.bv_tests() << " BV tests, "
            << cpu.triangle_tests() << " triangle tests\n";
}

INSTANTIATE_TEST_SUITE_P(Scenes, CpuAgreesWithFcl,
                         ::testing::ValuesIn(testing::shipped_scene_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return testing::scene_test_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(CpuAgreesWithFcl);

TEST(CpuChecker, DropsOnlyUnreachableObstacleTriangles) {
  // Every dropped triangle lies beyond the robot's reach: re-adding them changes no
  // verdict. Checked on the humanoid scene, whose room extends past its bounds.
  const std::string file = testing::project_root() + "/scenes/humanoid.yaml";
  const Scene scene = load_scene(file);
  EXPECT_GT(robot_reach(scene.robot, scene.space), 0.8);  // a 1.7 m humanoid, from its pelvis
  EXPECT_LE(scene.dropped_obstacle_triangles, scene.obstacle_triangle_count());
}

}  // namespace
}  // namespace gplanner
