// MilestoneSampler: the milestones depend on the seed and the order of the attempts
// alone, not on how the attempts are split into calls (the roadmap planner sizes its
// calls by time) nor on the streams being drawn on several threads; without the bridge
// test they are the free ones among the draws; every milestone is free, and the bridge
// test's lie in the gap between two walls.

#include "gplanner/planner/planning/milestone_sampler.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/plan_result.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

// The cube of side 0.2 between two walls 0.1 thick across x = -0.25 and x = 0.25: a gap
// 0.4 wide between them.
struct Sampling {
  Sampling() {
    folder.write("cube.obj", testing::kCubeObj);
    const std::string two_walls =
        testing::cube_scene("two_walls",
                            "  - {name: left, box: [0.1, 10, 10], pose: {xyz: [-0.25, 0, 0]}}\n"
                            "  - {name: right, box: [0.1, 10, 10], pose: {xyz: [0.25, 0, 0]}}\n");
    scene = std::make_unique<Scene>(load_scene(folder.write("scene.yaml", two_walls)));
    checker = std::make_unique<CpuChecker>(*scene);
  }
  // The milestones of `attempts` attempts made in calls of the sizes given, in turn.
  std::vector<float> milestones(const std::vector<std::size_t>& calls, const SamplerOptions& o) {
    MilestoneSampler sampler(scene->space, make_metric(scene->space, scene->planner), o);
    sampler.set_endpoints(scene->start.data(), scene->goal.data());
    std::mt19937_64 rng(7);
    std::vector<float> found;
    PlanTimes times;
    for (const std::size_t n : calls) sampler.sample(&rng, n, checker.get(), &found, &times);
    return found;
  }
  testing::ScratchFolder folder;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<CpuChecker> checker;
};

SamplerOptions bridges_and_spread() {
  SamplerOptions o;
  o.bridge_fraction = 0.5;
  o.bridge_sigma = 0.2;
  o.rotation_spread = 0.3;
  return o;
}

TEST(MilestoneSampler, TheSameMilestonesWhateverTheCallsAndThreads) {
  Sampling s;
  const SamplerOptions o = bridges_and_spread();
  // Several streams at once in one call (threads), against calls cut across the
  // streams' boundaries, one attempt at a time among them.
  constexpr std::size_t kStream = MilestoneSampler::kStreamAttempts;
  const std::vector<float> one_call = s.milestones({5 * kStream + 300}, o);
  const std::vector<float> in_parts =
      s.milestones({1, kStream - 2, 1, 1, 2 * kStream + 7, kStream + 280, kStream + 12}, o);
  ASSERT_FALSE(one_call.empty());
  EXPECT_EQ(one_call, in_parts);
  // Other calls again from the start: the same too.
  EXPECT_EQ(s.milestones({3 * kStream, 2 * kStream + 300}, o), one_call);
  // Another seed draws other milestones (the test could not tell otherwise).
  MilestoneSampler other(s.scene->space, make_metric(s.scene->space, s.scene->planner), o);
  other.set_endpoints(s.scene->start.data(), s.scene->goal.data());
  std::mt19937_64 rng(8);
  std::vector<float> found;
  PlanTimes times;
  other.sample(&rng, 5 * kStream + 300, s.checker.get(), &found, &times);
  EXPECT_NE(found, one_call);
}

// Without the bridge test (each attempt drawn straight into the batch): the milestones
// are the free ones among the draws, stream by stream, each stream's generator seeded by
// one draw of the caller's; the same whatever the calls.
TEST(MilestoneSampler, WithoutBridgesTheMilestonesAreTheFreeDraws) {
  Sampling s;
  SamplerOptions o;
  o.rotation_spread = 0.3;
  constexpr std::size_t kStream = MilestoneSampler::kStreamAttempts;
  const std::size_t attempts = 3 * kStream + 100;
  const std::vector<float> one_call = s.milestones({attempts}, o);
  EXPECT_EQ(s.milestones({1, kStream + 5, 2 * kStream - 7, 101}, o), one_call);
  MilestoneSampler sampler(s.scene->space, make_metric(s.scene->space, s.scene->planner), o);
  sampler.set_endpoints(s.scene->start.data(), s.scene->goal.data());
  const int width = s.scene->space.width();
  std::mt19937_64 rng(7), stream;
  std::vector<float> q(width), expected;
  std::size_t colliding = 0;
  for (std::size_t a = 0; a < attempts; ++a) {
    if (a % kStream == 0) stream.seed(rng());
    sampler.draw(&stream, q.data());
    std::uint8_t verdict = 0;
    s.checker->check(q.data(), 1, &verdict);
    if (verdict) {
      ++colliding;
    } else {
      expected.insert(expected.end(), q.begin(), q.end());
    }
  }
  EXPECT_GT(colliding, 0u);  // the walls take some: the test could tell a missed check
  EXPECT_EQ(one_call, expected);
}

TEST(MilestoneSampler, EveryMilestoneIsFreeBridgesToo) {
  Sampling s;
  SamplerOptions o = bridges_and_spread();
  o.bridge_fraction = 1;  // bridges only: milestones between the walls
  const std::vector<float> found = s.milestones({20000}, o);
  const int width = s.scene->space.width();
  ASSERT_GT(found.size() / width, 10u);
  std::vector<std::uint8_t> colliding(found.size() / width, 1);
  s.checker->check(found.data(), colliding.size(), colliding.data());
  std::size_t in_gap = 0;
  for (std::size_t i = 0; i < colliding.size(); ++i) {
    EXPECT_EQ(colliding[i], 0) << "milestone " << i;
    in_gap += std::abs(found[i * width]) < 0.2;
  }
  // A bridge's ends both collide and its midpoint is free: the gap (a tenth of the
  // bounds' length, where uniform samples would put a tenth of the milestones).
  EXPECT_GT(in_gap, 0.9 * colliding.size());
}

}  // namespace
}  // namespace gplanner
