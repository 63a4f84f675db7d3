// A stop raised from another thread (as gplan's SIGINT handler and OMPL's termination
// conditions do) is honoured within a slice of the stages (2 % of the time limit, here
// 5 s: 100 ms) and 100 ms more, whatever stage planning is in: sampling a
// huge first round, k-NN, edge batches, searches, shortcutting; on the cpu and fcl
// backends, with PRM and lazy PRM. A stopped plan is never a path with an unchecked
// edge: it is either no path, or one that FCL finds free.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

using Clock = std::chrono::steady_clock;

// Plans with a stop raised after 200 ms; returns how long solve() went on after it.
double seconds_past_the_stop(const Scene& scene, CollisionChecker* checker,
                             RoadmapStrategy strategy, std::size_t milestones,
                             PlanResult* result) {
  std::unique_ptr<NeighborFinder> neighbors =
      make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu");
  PlanOptions options = plan_options(scene);
  options.milestones = milestones;
  options.time_limit_s = 5;  // slices of 100 ms
  std::atomic<bool> stop{false};
  options.should_stop = [&] { return stop.load(); };
  RoadmapPlanner planner(scene, checker, neighbors.get(), strategy, options);
  Clock::time_point raised;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    raised = Clock::now();
    stop = true;
  });
  *result = planner.solve(scene.start.data(), scene.goal.data());
  const Clock::time_point returned = Clock::now();
  stopper.join();
  return std::chrono::duration<double>(returned - raised).count();
}

void expect_stops_promptly(const std::string& scene_file, const std::string& backend) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + scene_file);
  std::unique_ptr<CollisionChecker> checker;
  if (backend == "fcl") {
    checker = std::make_unique<FclChecker>(scene);
  } else {
    checker = std::make_unique<CpuChecker>(scene);
  }
  for (const RoadmapStrategy strategy : {RoadmapStrategy::kLazyPrm, RoadmapStrategy::kPrm}) {
    // The scene's own first round (the stop comes in k-NN, edges or the search), and three
    // million milestones (the stop comes while sampling; ten million of pr2_reach's, with
    // k = 30, need more memory than a CI machine's half).
    for (const std::size_t milestones : {plan_options(scene).milestones, std::size_t(3000000)}) {
      PlanResult result;
      const double late = seconds_past_the_stop(scene, checker.get(), strategy, milestones, &result);
      const std::string what = scene_file + " " + backend + " " + strategy_name(strategy) + " " +
                               std::to_string(milestones) + " milestones";
      if (result.solved) {  // solved before the stop: a path FCL finds free
        EXPECT_EQ(testing::path_problem(scene, result.path), "") << what;
        continue;
      }
      EXPECT_EQ(result.stop_reason, "stopped") << what;
      EXPECT_LT(late, 0.2) << what << ": went on " << late << " s after the stop";
    }
  }
}

TEST(RoadmapPlannerStop, HonouredWithinASliceOnTheCpuBackend) {
  for (const char* scene : {"piano.yaml", "humanoid.yaml", "pr2_reach.yaml"})
    expect_stops_promptly(scene, "cpu");
}

TEST(RoadmapPlannerStop, HonouredWithinASliceOnTheFclBackend) {
  for (const char* scene : {"piano.yaml", "humanoid.yaml", "pr2_reach.yaml"})
    expect_stops_promptly(scene, "fcl");
}

}  // namespace
}  // namespace gplanner
