// Path shortcutting: a lazy PRM path shortened on checkers whose calls cost nothing,
// a few thousand samples and as much as many samples (as the GPU's do): every shortened path is
// free at a tenth of the edge resolution; checking the next round's shortcuts with this round's
// fine check gives the same path in fewer calls; checking every shortcut finely at once takes one
// call a round.

#include "gplanner/planner/planning/path_shortcutting.h"

#include <gtest/gtest.h>

#include <random>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::CostlyCallChecker;

TEST(PathShortcutting, FewerCallsWhereCallsCostMoreThanSamples) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  CpuChecker cpu(scene);
  std::unique_ptr<NeighborFinder> neighbors =
      make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu");
  PlanOptions options = plan_options(scene);
  options.seed = 1;
  options.shortcut_rounds = 0;
  RoadmapPlanner planner(scene, &cpu, neighbors.get(), RoadmapStrategy::kLazyPrm, options);
  const PlanResult found = planner.solve(scene.start.data(), scene.goal.data());
  ASSERT_TRUE(found.solved) << found.stop_reason;
  ASSERT_GT(found.path.size() / scene.space.width(), 3u);

  const int rounds = 3, candidates = 64;
  // Calls cost: nothing (checked as before), as much as 4,096 configurations (the next
  // round's shortcuts checked with this round's fine check), as much as 2^20 (every
  // shortcut checked finely at once where that fits one call).
  const std::size_t costs[] = {0, 4096, 1u << 20};
  std::vector<float> paths[3];
  std::size_t calls[3];
  for (int c = 0; c < 3; ++c) {
    CostlyCallChecker checker(scene, costs[c]);
    LocalPlanner local(scene, &checker, options.local);
    LocalPlannerOptions fine_options = options.local;
    fine_options.resolution_fraction /= options.final_check_refinement;
    LocalPlanner fine(scene, &checker, fine_options);
    paths[c] = found.path;
    std::mt19937_64 rng(1);
    const double length =
        shortcut_path(scene.space, &local, &fine, nullptr, rounds, candidates, &rng, &paths[c]);
    EXPECT_EQ(testing::path_problem(scene, paths[c]), "") << "call cost " << costs[c];
    EXPECT_LT(length, found.length);
    calls[c] = local.stats().batches + fine.stats().batches;
    if (c > 0) EXPECT_EQ(fine.stats().batches, 0u);  // every call through `local`
  }
  // Checking the next round's shortcuts early changes nothing but the number of calls.
  EXPECT_EQ(paths[1], paths[0]);
  EXPECT_LT(calls[1], calls[0]);
  EXPECT_LE(calls[2], static_cast<std::size_t>(rounds));  // one call a round
  EXPECT_LT(calls[2], calls[0]);
}

}  // namespace
}  // namespace gplanner
