// The tolerance band is small and finite in every scene: delta_fraction of the scene's
// size, at most 1e-3 of the robot's own size; magnitudes float cannot hold within it
// are bad input. Each case a tiny scene written to a scratch folder.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/input_error.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

using gplanner::testing::ScratchFolder;

// A fixed-base arm: a 1 x 1 x 0.2 slab, a 0.1 cube lifted by `lift` (prismatic, LIFT_MAX)
// above z = 0.5, and a 0.2 cube turned by `turn` (revolute, +-TURN_MAX) about z below it.
// The slab and the 0.2 cube are the one checked pair.
std::string arm_urdf(const std::string& lift_max = "1", const std::string& turn_max = "3") {
  return R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><collision><geometry><box size="1 1 0.2"/></geometry></collision></link>
  <link name="link1"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="link2"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="lift" type="prismatic">
    <parent link="base"/><child link="link1"/><origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper=")" +
         lift_max + R"(" effort="1" velocity="1"/>
  </joint>
  <joint name="turn" type="revolute">
    <parent link="link1"/><child link="link2"/><origin xyz="0 0 -0.15"/><axis xyz="0 0 1"/>
    <limit lower="-)" +
         turn_max + R"(" upper=")" + turn_max + R"(" effort="1" velocity="1"/>
  </joint>
</robot>
)";
}

std::string arm_scene(const std::string& obstacles) {
  return "name: arm\nrobot:\n  urdf: arm.urdf\n  planned_joints: [lift, turn]\n" + obstacles +
         "start:\n  joints: {lift: 0.5, turn: 0}\ngoal:\n  joints: {lift: 0.8, turn: 1}\n";
}

std::string box_scene(const std::string& obstacles, const std::string& bounds) {
  return "name: box\nrobot:\n  mesh: box.obj\n" + obstacles + bounds +
         "start:\n  base: {xyz: [-1, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n"
         "goal:\n  base: {xyz: [1, 0, 0], quat_wxyz: [1, 0, 0, 0]}\n";
}

const char* const kSmallBounds = "bounds:\n  min: [-2, -2, -2]\n  max: [2, 2, 2]\n";

// Checks the arm at q on `backend`: free with the 0.2 cube well above the slab, in
// collision with it half inside the slab.
void expect_arm_verdicts(const Scene& scene, const std::string& backend) {
  const std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
  ASSERT_EQ(checker->backend(), backend) << "the backend asked for really ran";
  const std::vector<float> rows = {0.5f, 0.3f,    // cube from z = 0.75 to 0.95: free
                                   -0.2f, 1.0f};  // cube from z = 0.05 to 0.25: in the slab
  std::vector<std::uint8_t> verdicts(2);
  checker->check(rows.data(), 2, verdicts.data());
  EXPECT_EQ(verdicts[0], 0) << backend << ": a free configuration";
  EXPECT_EQ(verdicts[1], 1) << backend << ": a colliding one";
}

TEST(ToleranceBand, FixedBaseWithNoObstacleIsSmallAndFinite) {
  ScratchFolder scratch;
  scratch.write("arm.urdf", arm_urdf());
  const Scene scene = load_scene(scratch.write("scene.yaml", arm_scene("")));
  const ToleranceBand band = tolerance_band(scene);
  ASSERT_TRUE(std::isfinite(band.delta));
  EXPECT_GT(band.delta, 0);
  // The scene is everywhere the arm can reach: its reach (about 1.8 m) all round.
  EXPECT_GT(band.scene_size, 3.0);
  EXPECT_LT(band.scene_size, 8.0);
  EXPECT_DOUBLE_EQ(band.delta, 1e-5 * band.scene_size);
  EXPECT_FALSE(band.capped);
  expect_arm_verdicts(scene, "cpu");
  expect_arm_verdicts(scene, "fcl");
}

TEST(ToleranceBand, GpuFixedBaseWithNoObstacleIsSmallAndFinite) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  ScratchFolder scratch;
  scratch.write("arm.urdf", arm_urdf());
  const Scene scene = load_scene(scratch.write("scene.yaml", arm_scene("")));
  expect_arm_verdicts(scene, "gpu");
}

TEST(ToleranceBand, ALargeFloorIsCappedByTheRobotsSize) {
  ScratchFolder scratch;
  scratch.write("box.obj", testing::kCubeObj);
  const Scene scene = load_scene(scratch.write(
      "scene.yaml", box_scene("obstacles:\n  - box: [200, 200, 0.1]\n    pose: {xyz: [0, 0, -1]}\n",
                              kSmallBounds)));
  const ToleranceBand band = tolerance_band(scene);
  EXPECT_NEAR(band.robot_size, 0.2 * std::sqrt(3.0), 1e-7);
  EXPECT_GT(1e-5 * band.scene_size, band.delta) << "the scene's size alone gives 2.8 mm";
  EXPECT_TRUE(band.capped);
  EXPECT_DOUBLE_EQ(band.delta, kRobotBandFraction * band.robot_size);
  EXPECT_DOUBLE_EQ(tolerance_delta(scene), band.delta);
}

// Loading `scene_text` fails with an InputError whose message holds every one of
// `parts`.
void expect_refused(const ScratchFolder& scratch, const std::string& scene_text,
                    const std::vector<std::string>& parts) {
  const std::string file = scratch.write("scene.yaml", scene_text);
  try {
    load_scene(file);
    ADD_FAILURE() << "loaded:\n" << scene_text;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(file + ":", 0), 0u) << message;
    for (const std::string& part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' in: " << message;
  }
}

TEST(ToleranceBand, AnAbsurdObstacleScaleIsBadInput) {
  ScratchFolder scratch;
  scratch.write("box.obj", testing::kCubeObj);
  expect_refused(scratch,
                 box_scene("obstacles:\n  - mesh: box.obj\n    scale: [1e20, 1e20, 1]\n"
                           "    pose: {xyz: [0, 0, -1.5]}\n",
                           kSmallBounds),
                 {":5: obstacles[0]: obstacle", "spans", "float cannot place it"});
}

TEST(ToleranceBand, BoundsFarBeyondTheBandAreBadInput) {
  ScratchFolder scratch;
  scratch.write("box.obj", testing::kCubeObj);
  expect_refused(scratch,
                 box_scene("obstacles:\n  - box: [0.5, 0.5, 0.5]\n",
                           "bounds:\n  min: [-1e9, -1e9, -1e9]\n  max: [1e9, 1e9, 1e9]\n"),
                 {":7: bounds:", "the robot can reach", "give bounds around"});
}

TEST(ToleranceBand, APrismaticJointBeyondTheBandIsBadInput) {
  ScratchFolder scratch;
  scratch.write("arm.urdf", arm_urdf("1e12"));
  expect_refused(scratch, arm_scene(""), {":3: robot:", "the robot reaches", "prismatic"});
}

TEST(ToleranceBand, ARevoluteJointTurnedTooFarIsBadInput) {
  ScratchFolder scratch;
  scratch.write("arm.urdf", arm_urdf("1", "1e7"));
  expect_refused(scratch, arm_scene(""), {":3: robot:", "joint 'turn' turns to 1e+07 rad"});
}

}  // namespace
}  // namespace gplanner
