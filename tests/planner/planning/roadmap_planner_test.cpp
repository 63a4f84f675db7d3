// PRM and lazy PRM on the cpu backend: paths that FCL finds free at a tenth of the edge
// resolution, the same path for the same seed, roadmaps that carry over, and the time
// limit honoured.

#include "gplanner/planner/planning/roadmap_planner.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>
#include <utility>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/output/roadmap_file.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "require_gpu.h"
#include "test_support.h"

namespace gplanner {
namespace {

struct Planning {
  explicit Planning(const std::string& name)
      : scene(load_scene(testing::project_root() + "/scenes/" + name)),
        checker(scene),
        neighbors(make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu")) {}

  PlanResult plan(RoadmapStrategy strategy, unsigned long long seed, double limit = 300,
                  std::size_t milestones = 0) {
    PlanOptions options = plan_options(scene);
    options.seed = seed;
    if (milestones) options.milestones = milestones;
    options.time_limit_s = limit;
    RoadmapPlanner planner(scene, &checker, neighbors.get(), strategy, options);
    return planner.solve(scene.start.data(), scene.goal.data());
  }

  Scene scene;
  CpuChecker checker;
  std::unique_ptr<NeighborFinder> neighbors;
};

TEST(RoadmapPlanner, LazyPrmFindsAFreePathAndShortensIt) {
  Planning p("piano.yaml");
  const PlanResult result = p.plan(RoadmapStrategy::kLazyPrm, 1);
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(p.scene, result.path), "");
  EXPECT_LT(result.length, result.length_before_shortcut);
  // Lazy: far fewer edges checked than the roadmap holds.
  EXPECT_LT(result.edges_checked * 10, result.edges);
  EXPECT_GT(result.times.state_checks, 0);
  EXPECT_GT(result.times.knn, 0);
  EXPECT_GT(result.times.edge_checks, 0);
  EXPECT_GE(result.times.total, result.times.state_checks + result.times.knn +
                                    result.times.edge_checks + result.times.shortcutting);
}

// Every GPU call counted, in the stage that made it; none on the cpu backend. (A checker
// that counts each of its calls as a GPU call stands for the GPU.)
TEST(RoadmapPlanner, GpuCallsAreCountedPerStage) {
  Planning p("pr2_base_arm.yaml");
  const PlanResult on_cpu = p.plan(RoadmapStrategy::kLazyPrm, 1);
  ASSERT_TRUE(on_cpu.solved) << on_cpu.stop_reason;
  EXPECT_EQ(on_cpu.gpu_calls.total, 0u);
  testing::CostlyCallChecker costly(p.scene, 8192);
  PlanOptions options = plan_options(p.scene);
  options.seed = 1;
  RoadmapPlanner planner(p.scene, &costly, p.neighbors.get(), RoadmapStrategy::kLazyPrm, options);
  const std::size_t before = costly.device_calls();
  const PlanResult result = planner.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  const PlanGpuCalls& c = result.gpu_calls;
  EXPECT_EQ(c.total, costly.device_calls() - before);
  EXPECT_EQ(c.total, c.state_checks + c.knn + c.search + c.edge_checks + c.shortcutting);
  EXPECT_EQ(c.search, 0u);  // the costs to the goal on the host
  EXPECT_GT(c.state_checks, 0u);
  EXPECT_EQ(c.knn, 0u);  // the k-NN ran on the CPU
  EXPECT_GT(c.edge_checks, 0u);
  EXPECT_GT(c.shortcutting, 0u);
  // The first round's milestones in at most a few calls: the first batch as large as a
  // call's fixed cost.
  EXPECT_LE(c.state_checks, 3u);
}

// MotionBenchMaker's cage 0002: the goal inside a cage, the edges into it found invalid
// near the goal, which nearly every way passes; the search turns round (from the goal,
// led by the costs to the start: at 32bf351 its repairs took 464 ms of the cpu backend's
// 714 ms of search, 194 ms in all after). The path still runs from start to goal and
// passes the fine re-check.
TEST(RoadmapPlanner, TurnsRoundWhereInvalidEdgesCutMostWaysToTheGoal) {
  const std::string data = testing::shared_data();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)";
  const std::string panda = data + "/motionbenchmaker/panda";
  const testing::ScratchFolder folder;
  const std::string file = folder.write(
      "cage.yaml", "name: cage_0002\nrobot:\n  urdf: " + panda + "/robot/panda.urdf\n  srdf: " +
                       panda + "/robot/panda.srdf\n  packages: {meshes: " + panda +
                       "/robot/meshes}\nmoveit:\n  scene: " + panda +
                       "/problems/cage_panda/scene0002.yaml\n  request: " + panda +
                       "/problems/cage_panda/request0002.yaml\n");
  const Scene scene = load_scene(file);
  CpuChecker checker(scene);
  std::unique_ptr<NeighborFinder> neighbors =
      make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu");
  PlanOptions options = plan_options(scene);
  options.seed = 1;
  options.time_limit_s = 120;
  RoadmapPlanner planner(scene, &checker, neighbors.get(), RoadmapStrategy::kLazyPrm, options);
  const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_GT(result.rounds, 1u);
  EXPECT_EQ(testing::path_problem(scene, result.path), "");  // from start to goal, free
}

// Checking the next shortest paths' edges in the same batch finds the path of the same
// length (the shortest valid one in the roadmap) in far fewer checker calls.
TEST(RoadmapPlanner, LazyPrmBatchesTheNextShortestPaths) {
  Planning p("humanoid.yaml");
  PlanOptions options = plan_options(p.scene);
  options.seed = 3;
  options.shortcut_rounds = 0;
  ASSERT_GT(options.lazy_batch_paths, 1);
  PlanOptions one_path = options;
  one_path.lazy_batch_paths = 1;
  PlanResult results[2];
  for (int i = 0; i < 2; ++i) {
    RoadmapPlanner planner(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kLazyPrm,
                           i == 0 ? one_path : options);
    results[i] = planner.solve(p.scene.start.data(), p.scene.goal.data());
    ASSERT_TRUE(results[i].solved) << results[i].stop_reason;
    EXPECT_EQ(testing::path_problem(p.scene, results[i].path), "");
  }
  const PlanResult &single = results[0], &batched = results[1];
  EXPECT_EQ(single.rounds, batched.rounds);
  EXPECT_NEAR(batched.length, single.length, 1e-6 * single.length);
  EXPECT_GE(batched.edges_checked, single.edges_checked);
  EXPECT_GT(batched.searches, 0u);
  // One batch per search, and the fine re-check, without batching; a few with it.
  EXPECT_GE(single.edge_batches, single.searches - single.rounds);
  EXPECT_LT(batched.edge_batches * 4, single.edge_batches)
      << batched.edge_batches << " against " << single.edge_batches;
}

TEST(RoadmapPlanner, PrmChecksEveryEdgeAndFindsAFreePath) {
  Planning p("pr2_base_arm.yaml");
  const PlanResult result = p.plan(RoadmapStrategy::kPrm, 2, 300, 250);
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(p.scene, result.path), "");
  EXPECT_EQ(result.edges_checked, result.edges);
}

TEST(RoadmapPlanner, SameSeedSamePathOtherSeedOtherPath) {
  Planning p("pr2_base_arm.yaml");
  const PlanResult a = p.plan(RoadmapStrategy::kLazyPrm, 5);
  const PlanResult b = p.plan(RoadmapStrategy::kLazyPrm, 5);
  const PlanResult c = p.plan(RoadmapStrategy::kLazyPrm, 6);
  ASSERT_TRUE(a.solved && b.solved && c.solved);
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.milestones, b.milestones);
  EXPECT_NE(a.path, c.path);
}

TEST(RoadmapPlanner, TimeLimitStopsWithoutAPath) {
  Planning p("piano.yaml");
  PlanOptions options = plan_options(p.scene);
  options.milestones = 20000;  // far more than a millisecond allows
  options.time_limit_s = 0.001;
  RoadmapPlanner planner(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kLazyPrm,
                         options);
  const PlanResult result = planner.solve(p.scene.start.data(), p.scene.goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(result.stop_reason, "time limit");
  EXPECT_TRUE(result.path.empty());
}

TEST(RoadmapPlanner, StopConditionIsHonoured) {
  Planning p("piano.yaml");
  PlanOptions options = plan_options(p.scene);
  int polls = 0;
  options.should_stop = [&polls] { return ++polls > 2; };
  RoadmapPlanner planner(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kPrm, options);
  const PlanResult result = planner.solve(p.scene.start.data(), p.scene.goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(result.stop_reason, "stopped");
}

TEST(RoadmapPlanner, ASavedRoadmapIsUsedAgain) {
  Planning p("pr2_base_arm.yaml");
  PlanOptions options = plan_options(p.scene);
  options.milestones = 250;
  RoadmapPlanner first(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kPrm, options);
  const PlanResult a = first.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(a.solved);
  testing::ScratchFolder scratch;
  save_roadmap(first.roadmap(), p.scene, scratch.path() + "/r.roadmap");
  RoadmapPlanner second(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kPrm, options);
  second.set_roadmap(load_roadmap(p.scene, scratch.path() + "/r.roadmap"));
  const PlanResult b = second.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(b.solved);
  EXPECT_EQ(testing::path_problem(p.scene, b.path), "");
  // No new milestones: the loaded ones (plus this query's start and goal) sufficed, each
  // checked once, and only the edges of the new start and goal were checked.
  EXPECT_EQ(b.states_checked, a.milestones);
  EXPECT_EQ(b.milestones, a.milestones + 2);
  EXPECT_LT(b.edges_checked, a.edges_checked / 10);
}

// Every milestone joined to its k nearest among the milestones of its round, each pair
// once: the edges of new milestones are added without a search for them (append_edge),
// and must be those add_edge would have made. Five rounds (seed 3), each round's nearest
// found again by a finder of its own.
TEST(RoadmapPlanner, EachRoundJoinsItsMilestonesToTheirNearestOnce) {
  Planning p("pr2_base_arm.yaml");
  PlanOptions options = plan_options(p.scene);
  options.seed = 3;
  options.milestones = 100;
  RoadmapPlanner planner(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kLazyPrm,
                         options);
  const PlanResult result = planner.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  ASSERT_GE(result.rounds, 3);
  const Roadmap& roadmap = planner.roadmap();
  std::set<std::pair<std::uint32_t, std::uint32_t>> made, expected;
  for (const RoadmapEdge& e : roadmap.edges()) {
    EXPECT_LT(e.a, e.b);
    EXPECT_TRUE(made.emplace(e.a, e.b).second) << "edge " << e.a << "-" << e.b << " twice";
  }
  // The rounds: the start, the goal and `milestones`, then each round doubles the
  // milestones.
  std::unique_ptr<NeighborFinder> again =
      make_neighbor_finder(make_metric(p.scene.space, p.scene.planner), "cpu");
  std::size_t first = 0, n = 2 + options.milestones;
  for (int round = 0; round < result.rounds; ++round) {
    ASSERT_LE(n, roadmap.vertex_count());
    std::vector<int> nearest;
    ASSERT_TRUE(
        again->nearest_of(roadmap.vertices().data(), n, first, n, options.neighbors, &nearest));
    for (std::size_t v = first; v < n; ++v) {
      for (int j = 0; j < options.neighbors; ++j) {
        const int w = nearest[(v - first) * options.neighbors + j];
        if (w < 0) break;
        expected.emplace(std::min<std::uint32_t>(v, w), std::max<std::uint32_t>(v, w));
      }
    }
    first = n;
    n += std::max(options.milestones, n - 2);
  }
  EXPECT_EQ(first, roadmap.vertex_count());
  EXPECT_EQ(made, expected);
}

// The CPU finder asked as the GPU's is (every new milestone of a round in one call) or
// one new milestone a call.
class AskedAllOrOne : public NeighborFinder {
 public:
  AskedAllOrOne(NeighborFinder* finder, bool all) : finder_(finder), all_(all) {}
  std::string device() const override { return finder_->device(); }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    return finder_->nearest_of(points, n, first, end, k, indices);
  }
  bool searches_all_points() const override { return all_; }
  double query_cost(std::size_t) const override { return all_ ? 1 : 1e30; }

 private:
  NeighborFinder* finder_;
  bool all_;
};

// A round's new milestones are joined alike whether all come in one call (their edges
// chosen on all threads, then appended at once) or one a call (each edge to a new
// milestone of an earlier call looked for): the same edges in the same order, with the
// same lengths and states, and the same plan.
TEST(RoadmapPlanner, JoinsNewMilestonesAlikeAllAtOnceOrOneAtATime) {
  Planning p("pr2_base_arm.yaml");
  PlanOptions options = plan_options(p.scene);
  options.seed = 3;
  options.milestones = 100;
  AskedAllOrOne all(p.neighbors.get(), true), one(p.neighbors.get(), false);
  RoadmapPlanner at_once(p.scene, &p.checker, &all, RoadmapStrategy::kLazyPrm, options);
  const PlanResult a = at_once.solve(p.scene.start.data(), p.scene.goal.data());
  RoadmapPlanner singly(p.scene, &p.checker, &one, RoadmapStrategy::kLazyPrm, options);
  const PlanResult b = singly.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(a.solved && b.solved);
  ASSERT_GE(a.rounds, 3);
  const std::vector<RoadmapEdge>& ea = at_once.roadmap().edges();
  const std::vector<RoadmapEdge>& eb = singly.roadmap().edges();
  ASSERT_EQ(ea.size(), eb.size());
  for (std::size_t e = 0; e < ea.size(); ++e) {
    ASSERT_EQ(std::make_tuple(ea[e].a, ea[e].b, ea[e].length, ea[e].state),
              std::make_tuple(eb[e].a, eb[e].b, eb[e].length, eb[e].state))
        << "edge " << e;
  }
  EXPECT_EQ(a.path, b.path);
}

// The GPU finder with its GPU for the costs to the goal hidden: the host computes them.
class WithoutWayCosts : public NeighborFinder {
 public:
  explicit WithoutWayCosts(NeighborFinder* finder) : finder_(finder) {}
  std::string device() const override { return finder_->device(); }
  bool nearest_of(const float* points, std::size_t n, std::size_t first, std::size_t end, int k,
                  std::vector<int>* indices) override {
    return finder_->nearest_of(points, n, first, end, k, indices);
  }
  bool searches_all_points() const override { return finder_->searches_all_points(); }
  double query_cost(std::size_t n) const override { return finder_->query_cost(n); }
  std::size_t device_calls() const override { return finder_->device_calls(); }
  void reset() override { finder_->reset(); }

 private:
  NeighborFinder* finder_;
};

// Lazy PRM on the piano (rounds of 16,000 and 32,000 milestones) with its costs to the goal
// computed on the GPU: the rounds, searches and path of the host's costs (the same costs,
// bit for bit), the GPU's calls counted in the search stage.
TEST(RoadmapPlannerGpu, CostsToTheGoalOnTheGpuGiveTheHostsPlan) {
  REQUIRE_GPU();
  Planning p("piano.yaml");
  std::unique_ptr<NeighborFinder> gpu =
      make_neighbor_finder(make_metric(p.scene.space, p.scene.planner), "gpu");
  ASSERT_NE(gpu->way_costs(), nullptr);
  WithoutWayCosts host(gpu.get());
  PlanOptions options = plan_options(p.scene);
  options.seed = 1;
  RoadmapPlanner with_gpu(p.scene, &p.checker, gpu.get(), RoadmapStrategy::kLazyPrm, options);
  const PlanResult a = with_gpu.solve(p.scene.start.data(), p.scene.goal.data());
  RoadmapPlanner on_host(p.scene, &p.checker, &host, RoadmapStrategy::kLazyPrm, options);
  const PlanResult b = on_host.solve(p.scene.start.data(), p.scene.goal.data());
  ASSERT_TRUE(a.solved && b.solved);
  EXPECT_GE(a.milestones, 2 * GoalDistances::kGpuVertices);
  EXPECT_EQ(a.rounds, b.rounds);
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(testing::path_problem(p.scene, a.path), "");
  EXPECT_GT(a.gpu_calls.search, 0u);
  EXPECT_EQ(b.gpu_calls.search, 0u);
  EXPECT_EQ(a.gpu_calls.total, a.gpu_calls.state_checks + a.gpu_calls.knn + a.gpu_calls.search +
                                   a.gpu_calls.edge_checks + a.gpu_calls.shortcutting);
}

// Checks each progress report of the planner it watches (set `watched` once it is made
// with the options given): its count of valid edges must be the roadmap's.
struct ValidEdgeCounts {
  explicit ValidEdgeCounts(PlanOptions* options) {
    options->progress = [this](const PlanProgress& progress) {
      std::size_t valid = 0;
      for (const RoadmapEdge& e : watched->roadmap().edges()) valid += e.state == EdgeState::kValid;
      EXPECT_EQ(progress.edges_valid, valid) << progress.stage << ", round " << progress.round;
      most_valid = std::max(most_valid, valid);
      ++reports;
    };
  }
  const RoadmapPlanner* watched = nullptr;
  std::size_t reports = 0, most_valid = 0;
};

// Every progress report's count of valid edges is the roadmap's, on PRM (most edges
// checked), lazy PRM (edges set aside and back) and a loaded roadmap (its file's states,
// then its milestones checked).
TEST(RoadmapPlanner, ProgressCountsTheValidEdges) {
  Planning p("pr2_base_arm.yaml");
  testing::ScratchFolder scratch;
  for (const RoadmapStrategy strategy : {RoadmapStrategy::kPrm, RoadmapStrategy::kLazyPrm}) {
    PlanOptions options = plan_options(p.scene);
    options.milestones = 250;
    options.seed = 1;
    ValidEdgeCounts counts(&options);
    RoadmapPlanner first(p.scene, &p.checker, p.neighbors.get(), strategy, options);
    counts.watched = &first;
    ASSERT_TRUE(first.solve(p.scene.start.data(), p.scene.goal.data()).solved);
    EXPECT_GT(counts.reports, 2u);
    EXPECT_GT(counts.most_valid, 0u);
    save_roadmap(first.roadmap(), p.scene, scratch.path() + "/r.roadmap");
    RoadmapPlanner second(p.scene, &p.checker, p.neighbors.get(), strategy, options);
    second.set_roadmap(load_roadmap(p.scene, scratch.path() + "/r.roadmap"));
    counts.watched = &second;
    counts.reports = 0;
    ASSERT_TRUE(second.solve(p.scene.start.data(), p.scene.goal.data()).solved);
    EXPECT_GT(counts.reports, 0u);
  }
}

// A roadmap file is input: a milestone in an obstacle, in a file with a valid checksum,
// loses its edges (even those the file calls valid) before any search.
TEST(RoadmapPlanner, ALoadedMilestoneInAnObstacleLosesItsEdges) {
  Planning p("piano.yaml");
  const int width = p.scene.space.width();
  std::mt19937_64 rng(7);
  std::vector<float> inside(width), free_q(width);
  std::uint8_t verdict = 0;
  do {
    p.scene.space.sample_uniform(&rng, inside.data());
    p.checker.check(inside.data(), 1, &verdict);
  } while (!verdict);
  do {
    p.scene.space.sample_uniform(&rng, free_q.data());
    p.checker.check(free_q.data(), 1, &verdict);
  } while (verdict);
  Roadmap crafted(width);
  crafted.add_vertex(p.scene.start.data());
  crafted.add_vertex(p.scene.goal.data());
  crafted.add_vertex(inside.data());
  crafted.add_vertex(free_q.data());
  crafted.add_edge(0, 2, 0.0f, EdgeState::kValid);  // lengths and states as a forger wrote them
  crafted.add_edge(1, 2, 0.0f, EdgeState::kValid);
  crafted.add_edge(0, 3, 0.0f, EdgeState::kUnknown);
  testing::ScratchFolder scratch;
  save_roadmap(crafted, p.scene, scratch.path() + "/r.roadmap");
  PlanOptions options = plan_options(p.scene);
  options.milestones = 200;
  options.time_limit_s = 2;
  // The progress reports count the valid edges as the roadmap has them: the file's two
  // valid edges no longer, once their milestone is found colliding.
  ValidEdgeCounts counts(&options);
  RoadmapPlanner planner(p.scene, &p.checker, p.neighbors.get(), RoadmapStrategy::kLazyPrm,
                         options);
  counts.watched = &planner;
  planner.set_roadmap(load_roadmap(p.scene, scratch.path() + "/r.roadmap"));
  const PlanResult result = planner.solve(p.scene.start.data(), p.scene.goal.data());
  EXPECT_GT(counts.reports, 0u);
  if (result.solved) EXPECT_EQ(testing::path_problem(p.scene, result.path), "");
  const Roadmap& roadmap = planner.roadmap();
  EXPECT_EQ(roadmap.edge(0).state, EdgeState::kInvalid);
  EXPECT_EQ(roadmap.edge(1).state, EdgeState::kInvalid);
  // Lengths recomputed under the metric, not taken from the file.
  EXPECT_GT(roadmap.edge(2).length, 0.0f);
}

}  // namespace
}  // namespace gplanner
