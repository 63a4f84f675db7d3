// Path shortcutting: a lazy PRM path shortened on a checker whose calls cost little and
// on one whose calls cost as much as many samples (as the GPU's do); both shortened
// paths are free at a tenth of the edge resolution, and the second takes one call a
// round.

#include "gplanner/planner/path_shortcutting.h"

#include <gtest/gtest.h>

#include <random>

#include "gplanner/planner/cpu_checker.h"
#include "gplanner/planner/roadmap_planner.h"
#include "gplanner/planner/scene.h"
#include "gplanner/planner/scene_metric.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

// The cpu backend, saying that a call costs as much as `per_call` configurations.
class CostlyCallChecker : public CollisionChecker {
 public:
  CostlyCallChecker(const Scene& scene, std::size_t per_call) : cpu_(scene), per_call_(per_call) {}
  std::string backend() const override { return cpu_.backend(); }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override {
    cpu_.check(configurations, n, verdicts);
  }
  std::size_t configurations_per_call_cost() const override { return per_call_; }

 private:
  CpuChecker cpu_;
  std::size_t per_call_;
};

TEST(PathShortcutting, OneCallARoundWhereCallsCostMoreThanSamples) {
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

  const int rounds = 2, candidates = 64;
  std::size_t calls[2];
  double lengths[2];
  for (const int costly : {0, 1}) {
    CostlyCallChecker checker(scene, costly ? 1u << 20 : 0u);
    LocalPlanner local(scene, &checker, options.local);
    LocalPlannerOptions fine_options = options.local;
    fine_options.resolution_fraction /= options.final_check_refinement;
    LocalPlanner fine(scene, &checker, fine_options);
    std::vector<float> path = found.path;
    std::mt19937_64 rng(1);
    lengths[costly] = shortcut_path(scene.space, &local, &fine, rounds, candidates, &rng, &path);
    EXPECT_EQ(testing::path_problem(scene, path), "") << (costly ? "costly calls" : "cheap calls");
    EXPECT_LT(lengths[costly], found.length);
    calls[costly] = local.stats().batches + fine.stats().batches;
    if (costly) {
      EXPECT_EQ(local.stats().batches, 0u);  // every shortcut checked finely, at once
      EXPECT_LE(fine.stats().batches, static_cast<std::size_t>(rounds));
    } else {
      EXPECT_GT(local.stats().batches, 0u);
    }
  }
  EXPECT_LT(calls[1], calls[0]);
}

}  // namespace
}  // namespace gplanner
