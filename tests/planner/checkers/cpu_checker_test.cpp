// The cpu backend (the collision core on host threads) against FCL on every shipped
// scene: never a missed collision, extra collisions only within the tolerance band.

#include "gplanner/planner/checkers/cpu_checker.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/scene/scene_collision_model.h"
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

TEST(CpuChecker, DropsOnlyUnreachableObstacleGeometry) {
  // A unit cube robot (reach sqrt(3)/2 from its centre) whose centre stays in
  // [-1, 1]^3: it can touch nothing beyond 1 + 0.866 on any axis.
  testing::ScratchFolder scratch;
  scratch.write("cube.obj",
                "v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv -0.5 0.5 -0.5\nv 0.5 0.5 -0.5\n"
                "v -0.5 -0.5 0.5\nv 0.5 -0.5 0.5\nv -0.5 0.5 0.5\nv 0.5 0.5 0.5\n"
                "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
                "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n");
  const std::string file = scratch.write("scene.yaml", R"(robot: {mesh: cube.obj}
obstacles:
  - {name: near, box: [0.2, 0.2, 0.2], pose: {xyz: [0, 0, 1.5]}}
  - {name: far, box: [1, 1, 1], pose: {xyz: [10, 0, 0]}}
  - {name: straddling, box: [1, 1, 1], pose: {xyz: [2, 0, 0]}}
  - {name: straddling_surface, box: [1, 1, 1], pose: {xyz: [0, 2, 0]}, solid: false}
bounds: {min: [-1, -1, -1], max: [1, 1, 1]}
start: {base: {xyz: [-0.5, 0, -0.5], quat_wxyz: [1, 0, 0, 0]}}
goal: {base: {xyz: [0.5, 0, -0.5], quat_wxyz: [1, 0, 0, 0]}}
)");
  const Scene scene = load_scene(file);
  EXPECT_NEAR(robot_reach(scene.robot, scene.space), std::sqrt(3.0) / 2, 1e-9);
  // The far box goes whole. The straddling one (x in [1.5, 2.5]) is a solid and stays
  // whole; of the same box as a surface (y in [1.5, 2.5]) only the two triangles of its
  // face at y = 2.5, wholly beyond 1.866, are dropped.
  EXPECT_EQ(scene.dropped_obstacle_triangles, 12u + 2u);
  ASSERT_EQ(scene.obstacles.size(), 3u);
  EXPECT_EQ(scene.obstacles[0].name, "near");
  EXPECT_EQ(scene.obstacles[0].mesh_S.triangle_count(), 12u);
  EXPECT_EQ(scene.obstacles[1].name, "straddling");
  EXPECT_EQ(scene.obstacles[1].mesh_S.triangle_count(), 12u);
  EXPECT_EQ(scene.obstacles[2].name, "straddling_surface");
  EXPECT_EQ(scene.obstacles[2].mesh_S.triangle_count(), 10u);
}

}  // namespace
}  // namespace gplanner
