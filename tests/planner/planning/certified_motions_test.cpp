// Certified motions against answers known by construction: a thin wall that sampled
// edges at a coarse resolution jump over and certified edges catch; motions beside the
// wall with millimetres of clearance certified free; and on a real scene, every motion
// certified free is free under FCL at a resolution 100 times finer than the planner's.
// On every backend (GPU cases named Gpu, skipped without a device), and on the cpu backend
// with calls as costly as the GPU's.

#include "gplanner/planner/planning/certified_motions.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/path_recheck.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

std::vector<float> at(const Scene& scene, double x, double y) {
  std::vector<float> q(scene.space.width(), 0.0f);
  const std::vector<double> values = {x, y, 0, 1, 0, 0, 0};
  scene.space.from_file_values(values.data(), q.data());
  return q;
}

// A backend by name; "costly": the cpu backend with calls that cost as much as 8,192
// configurations, as the GPU's do (rounds of one call, segments cut into quarters);
// "costly16": as much as 16, fewer than a round's ends (the failing ends' plain checks
// then go into the next round's call).
std::unique_ptr<CollisionChecker> make_checker(const Scene& scene, const std::string& name) {
  if (name == "costly") return std::make_unique<testing::CostlyCallChecker>(scene, 8192);
  if (name == "costly16") return std::make_unique<testing::CostlyCallChecker>(scene, 16);
  std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, name);
  EXPECT_EQ(checker->backend(), name);
  return checker;
}

class CertifiedMotionsOn : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    if (GetParam() == "gpu") {
      const GpuDevice device = query_gpu_device();
      if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
    }
    folder_.write("cube.obj", testing::kCubeObj);
    scene_ = std::make_unique<Scene>(
        load_scene(folder_.write("wall.yaml", testing::kCubeAndThinWallScene)));
    checker_ = make_checker(*scene_, GetParam());
  }
  testing::ScratchFolder folder_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<CollisionChecker> checker_;
};

TEST_P(CertifiedMotionsOn, CatchAThinWallThatCoarseSamplesJumpOver) {
  // From x = -0.5 to 0.9: at 30 % of the 4 m extent a step, the one sample lies at
  // x = 0.2, clear of the wall; the cube crosses it on the way.
  const std::vector<float> a = at(*scene_, -0.5, 0), b = at(*scene_, 0.9, 0);
  LocalPlannerOptions coarse;
  coarse.resolution_fraction = 0.3;
  LocalPlanner sampled(*scene_, checker_.get(), coarse);
  std::uint8_t invalid = 9;
  sampled.check_motions(a.data(), b.data(), 1, &invalid);
  EXPECT_EQ(invalid, 0) << "the sampled check was to jump the wall";
  CertifiedMotions certified(*scene_, checker_.get());
  ASSERT_TRUE(certified.check_motions(a.data(), b.data(), 1, &invalid));
  EXPECT_EQ(invalid, 1);
}

TEST_P(CertifiedMotionsOn, CertifyMotionsBesideTheWallWithMillimetresToSpare) {
  // Along the wall, the cube's face 3 mm from it; and in the open.
  const double x = -0.01 - 0.1 - 0.003;
  const std::vector<float> beside_a = at(*scene_, x, -1), beside_b = at(*scene_, x, 1);
  const std::vector<float> open_a = at(*scene_, -1.5, -1), open_b = at(*scene_, -0.8, 1.2);
  std::vector<float> from = beside_a, to = beside_b;
  from.insert(from.end(), open_a.begin(), open_a.end());
  to.insert(to.end(), open_b.begin(), open_b.end());
  CertifiedMotionOptions options;
  options.step = 0.05;  // clearances of 25 mm to begin with: refined near the wall
  CertifiedMotions certified(*scene_, checker_.get(), options);
  std::uint8_t invalid[2] = {9, 9};
  ASSERT_TRUE(certified.check_motions(from.data(), to.data(), 2, invalid));
  EXPECT_EQ(invalid[0], 0) << "3 mm of clearance: certified after refining";
  EXPECT_EQ(invalid[1], 0);
  // Segments halved a round (CPU backends) or quartered in one call a round (where calls
  // cost: the GPU's, "costly").
  const bool calls_cost = checker_->configurations_per_call_cost() > 0;
  EXPECT_GT(certified.stats().rounds, calls_cost ? 2u : 3u)
      << "the motion along the wall needed finer segments";
  if (calls_cost) EXPECT_EQ(certified.stats().batches, certified.stats().rounds);
  // 0.5 mm into the wall: never certified.
  const std::vector<float> touching_a = at(*scene_, -0.01 - 0.1 + 0.0005, -1);
  const std::vector<float> touching_b = at(*scene_, -0.01 - 0.1 + 0.0005, 1);
  ASSERT_TRUE(certified.check_motions(touching_a.data(), touching_b.data(), 1, invalid));
  EXPECT_EQ(invalid[0], 1);
}

INSTANTIATE_TEST_SUITE_P(Backends, CertifiedMotionsOn,
                         ::testing::Values("cpu", "fcl", "costly", "costly16", "gpu"),
                         [](const auto& info) {
                           return info.param == "gpu" ? std::string("Gpu") : info.param;
                         });

// Every motion certified free on a real scene is free under FCL 100 times finer than the
// planner's resolution, and most short motions are certified.
class CertifiedMotionsAgree : public ::testing::TestWithParam<std::string> {};

TEST_P(CertifiedMotionsAgree, CertifiedFreeMotionsPassFclAHundredTimesFiner) {
  if (GetParam() == "gpu") {
    const GpuDevice device = query_gpu_device();
    if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  }
  // A rigid robot, and an articulated one whose checked link pairs stay close.
  for (const char* name : {"piano.yaml", "pr2_reach.yaml"}) {
    const Scene scene = load_scene(testing::project_root() + "/scenes/" + name);
    std::unique_ptr<CollisionChecker> checker = make_checker(scene, GetParam());
    const std::size_t width = scene.space.width();
    // Short motions between free configurations (as a roadmap's edges are).
    const std::vector<float> q = testing::sample_configurations(scene, 4000, 11);
    std::vector<std::uint8_t> colliding(4000);
    checker->check(q.data(), 4000, colliding.data());
    std::vector<float> free;
    for (std::size_t i = 0; i < 4000; ++i)
      if (!colliding[i]) free.insert(free.end(), &q[i * width], &q[(i + 1) * width]);
    // FCL's distances (the fcl backend's clearances) and its fine re-check take long on
    // the PR2: fewer motions there.
    const bool articulated = scene.robot.links.size() > 1;
    const std::size_t wanted = !articulated ? 60 : GetParam() == "fcl" ? 10 : 30;
    const std::size_t count = std::min(wanted, free.size() / width / 2);
    ASSERT_EQ(count, wanted) << name;
    std::vector<float> from(count * width), to(count * width);
    for (std::size_t m = 0; m < count; ++m) {
      std::copy_n(&free[(2 * m) * width], width, &from[m * width]);
      // A tenth of the way toward another free configuration: a roadmap edge's length.
      scene.space.interpolate(&free[(2 * m) * width], &free[(2 * m + 1) * width], 0.1,
                              &to[m * width]);
    }
    std::vector<std::uint8_t> invalid(count);
    CertifiedMotions certified(scene, checker.get());
    ASSERT_TRUE(certified.check_motions(from.data(), to.data(), count, invalid.data()));
    std::size_t certified_free = 0;
    for (std::size_t m = 0; m < count; ++m) {
      if (invalid[m]) continue;
      ++certified_free;
      std::vector<float> motion(&from[m * width], &from[m * width] + width);
      motion.insert(motion.end(), &to[m * width], &to[(m + 1) * width]);
      EXPECT_EQ(path_recheck_problem(scene, motion, 100, false), "") << name << " motion " << m;
    }
    // Most short motions between free configurations are free; certification that
    // refused them all would make planning impossible.
    EXPECT_GT(certified_free, count / 2) << name << ": " << certified_free << " of " << count;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, CertifiedMotionsAgree, ::testing::Values("cpu", "fcl", "costly", "gpu"),
                         [](const auto& info) {
                           return info.param == "gpu" ? std::string("Gpu") : info.param;
                         });

// Where a round's ends outnumber a call's cost, the failing ends' plain checks wait for
// the next round's call: the verdicts are those of plain checks in the same call, motion
// for motion, on motions between uniform configurations (many ends colliding) and short
// ones between free configurations; and the calls are fewer.
TEST(CertifiedMotions, DeferredPlainChecksGiveTheSameVerdicts) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/piano.yaml");
  const std::size_t width = scene.space.width();
  const std::vector<float> q = testing::sample_configurations(scene, 1000, 5);
  std::vector<std::uint8_t> colliding(1000);
  testing::CostlyCallChecker reference(scene, 8192), deferring(scene, 16);
  reference.check(q.data(), 1000, colliding.data());
  std::vector<float> from, to, free;
  for (std::size_t i = 0; i < 1000; ++i)
    if (!colliding[i]) free.insert(free.end(), &q[i * width], &q[(i + 1) * width]);
  for (std::size_t m = 0; m < 40; ++m) {  // uniform to uniform
    from.insert(from.end(), &q[(2 * m) * width], &q[(2 * m + 1) * width]);
    to.insert(to.end(), &q[(2 * m + 1) * width], &q[(2 * m + 2) * width]);
  }
  ASSERT_GE(free.size() / width, 40u);
  std::vector<float> near(width);
  for (std::size_t m = 0; m < 20; ++m) {  // free, a tenth of the way to another
    from.insert(from.end(), &free[(2 * m) * width], &free[(2 * m + 1) * width]);
    scene.space.interpolate(&free[(2 * m) * width], &free[(2 * m + 1) * width], 0.1, near.data());
    to.insert(to.end(), near.begin(), near.end());
  }
  const std::size_t count = from.size() / width;
  std::vector<std::uint8_t> want(count), got(count);
  CertifiedMotions in_one_call(scene, &reference), deferred(scene, &deferring);
  ASSERT_TRUE(in_one_call.check_motions(from.data(), to.data(), count, want.data()));
  ASSERT_TRUE(deferred.check_motions(from.data(), to.data(), count, got.data()));
  std::size_t invalid = 0;
  for (std::size_t m = 0; m < count; ++m) {
    EXPECT_EQ(got[m], want[m]) << "motion " << m;
    invalid += want[m];
  }
  // Both kinds present, or the comparison says little.
  EXPECT_GT(invalid, 20u);
  EXPECT_LT(invalid, count);
  // Plain checks of all ends in the round's call (cost 8,192) against those of the failing
  // ends in the next round's (cost 16): no call of their own either way.
  EXPECT_EQ(in_one_call.stats().batches, in_one_call.stats().rounds);
  EXPECT_LE(deferred.stats().batches, deferred.stats().rounds + 1);
}

}  // namespace
}  // namespace gplanner
