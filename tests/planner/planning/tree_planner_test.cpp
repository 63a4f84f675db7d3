// Batched RRT-Connect (TreePlanner) and the planner choice "auto", against answers known
// by construction: the only way through a wall is its hole; a closed wall has no way
// through, even where the trees' sampled checks jump it; the same seed gives the same
// path; the time limit and a stop are honoured, on the host within a round's lanes too;
// one checker call a round; auto takes lazy PRM for the piano and the trees for the PR2.
// And on real problems: MotionBenchMaker's shelf where lazy PRM found no path in 10 s, and
// the PR2 on the GPU; each path passes FCL's fine re-check.

#include "gplanner/planner/planning/tree_planner.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "gplanner/common/gpu_device.h"
#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/planner_choice.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

// The cube of side 0.2 from x = -1 to x = 1 through a wall 2 cm thick across x = 0 whose
// only opening is a square hole of side 0.4 about y = 0.8, z = 0.4.
std::string wall_with_a_hole() {
  return testing::cube_scene(
      "wall_with_a_hole",
      "  - {name: below, box: [0.02, 10, 5.2], pose: {xyz: [0, 0, -2.4]}}\n"
      "  - {name: above, box: [0.02, 10, 4.4], pose: {xyz: [0, 0, 2.8]}}\n"
      "  - {name: left, box: [0.02, 5.6, 0.4], pose: {xyz: [0, -2.2, 0.4]}}\n"
      "  - {name: right, box: [0.02, 4, 0.4], pose: {xyz: [0, 3, 0.4]}}\n");
}

struct Problem {
  explicit Problem(const std::string& scene_text) {
    folder.write("cube.obj", testing::kCubeObj);
    scene = std::make_unique<Scene>(load_scene(folder.write("scene.yaml", scene_text)));
    checker = std::make_unique<CpuChecker>(*scene);
  }
  PlanOptions options(unsigned long long seed, double limit = 60) const {
    PlanOptions o = plan_options(*scene);
    o.seed = seed;
    o.time_limit_s = limit;
    return o;
  }
  PlanResult plan(const PlanOptions& o) {
    TreePlanner planner(*scene, checker.get(), o);
    return planner.solve(scene->start.data(), scene->goal.data());
  }
  testing::ScratchFolder folder;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<CpuChecker> checker;
};

// Where the path's centre crosses x = 0 (the wall's plane): y and z, by interpolating
// the waypoints on either side (the cube does not turn far enough to matter here: its
// centre must pass within the hole less half its side, whatever its rotation).
std::vector<std::pair<double, double>> wall_crossings(const std::vector<float>& path, int width) {
  std::vector<std::pair<double, double>> crossings;
  for (std::size_t i = 0; i + 1 < path.size() / width; ++i) {
    const float* a = &path[i * width];
    const float* b = &path[(i + 1) * width];
    if ((a[0] < 0) == (b[0] < 0)) continue;
    const double t = a[0] / (a[0] - b[0]);
    crossings.push_back({a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])});
  }
  return crossings;
}

TEST(TreePlanner, GoesThroughTheOnlyHoleOfAWall) {
  Problem p(wall_with_a_hole());
  const PlanResult result = p.plan(p.options(1));
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(*p.scene, result.path), "");
  const int width = p.scene->space.width();
  const auto crossings = wall_crossings(result.path, width);
  ASSERT_FALSE(crossings.empty());
  for (const auto& [y, z] : crossings) {
    // The hole spans y in [0.6, 1.0], z in [0.2, 0.6]; the cube's centre is at least
    // 0.1 (half its side) inside, less the wall's half thickness reached at a slant.
    EXPECT_GT(y, 0.6);
    EXPECT_LT(y, 1.0);
    EXPECT_GT(z, 0.2);
    EXPECT_LT(z, 0.6);
  }
  EXPECT_EQ(result.stop_reason, "solved");
  EXPECT_GT(result.rounds, 1u);  // the straight way is blocked
  EXPECT_LE(result.length, result.length_before_shortcut);
  EXPECT_EQ(result.gpu_calls.total, 0u);
}

TEST(TreePlanner, NoPathThroughAClosedWallEvenWhereSamplesJumpIt) {
  Problem p(testing::kCubeAndThinWallScene);
  PlanOptions options = p.options(1, 1.0);
  // Samples a fifth of the space apart: the trees' checks jump the wall, and joined trees
  // bring paths through it to the certification, which must refuse every one.
  options.local.resolution_fraction = 0.2;
  TreePlanner planner(*p.scene, p.checker.get(), options);
  const auto started = std::chrono::steady_clock::now();
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_FALSE(result.solved);
  EXPECT_TRUE(result.path.empty());
  EXPECT_EQ(result.stop_reason, "time limit");
  EXPECT_LT(seconds, 1.0 + 0.1);
  EXPECT_GT(result.rounds, 10u);
  EXPECT_GT(planner.paths_refused(), 0u) << "the trees were to join through the wall";
}

TEST(TreePlanner, NoPathThroughAClosedWallWithTheFineRecheckEither) {
  Problem p(testing::kCubeAndThinWallScene);
  PlanOptions options = p.options(1, 0.5);
  options.local.resolution_fraction = 0.2;
  options.certify_path = false;  // re-checked at a tenth of the resolution instead
  TreePlanner planner(*p.scene, p.checker.get(), options);
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(result.stop_reason, "time limit");
  EXPECT_GT(planner.paths_refused(), 0u);
}

TEST(TreePlanner, SameSeedSamePathOtherSeedOtherPath) {
  Problem p(wall_with_a_hole());
  const PlanResult a = p.plan(p.options(3));
  const PlanResult b = p.plan(p.options(3));
  const PlanResult c = p.plan(p.options(4));
  ASSERT_TRUE(a.solved && b.solved && c.solved);
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.rounds, b.rounds);
  EXPECT_NE(a.path, c.path);
}

TEST(TreePlanner, StopConditionIsHonoured) {
  Problem p(testing::kCubeAndThinWallScene);
  PlanOptions options = p.options(1, 300);
  const auto started = std::chrono::steady_clock::now();
  options.should_stop = [&] {
    return std::chrono::steady_clock::now() - started > std::chrono::milliseconds(200);
  };
  const PlanResult result = p.plan(options);
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(result.stop_reason, "stopped");
  EXPECT_LT(result.times.total, 0.2 + 0.1);
}

TEST(TreePlanner, AStopEndsARoundsLanesOnTheHost) {
  // The closed wall: no way through, the lanes' extensions and connections long. A stop
  // that comes in the middle of a round (once 40 rows are checked) ends every lane at its
  // next row: after it, each thread checks at most the row it had begun. (Before, each
  // lane went on to the end of its extension and connection: the round's hundreds of
  // rows.)
  Problem p(testing::kCubeAndThinWallScene);
  PlanOptions options = p.options(1);
  options.tree_lanes = 8;
  constexpr std::size_t kStopAt = 40;
  testing::CostlyCallChecker counting(*p.scene, 0);  // calls that cost nothing: the host's way
  options.should_stop = [&] { return counting.checked() >= kStopAt; };
  TreePlanner planner(*p.scene, &counting, options);
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(result.stop_reason, "stopped");
  EXPECT_EQ(result.rounds, 1u);  // the stop came in the first round
  EXPECT_LE(counting.checked(), kStopAt + static_cast<std::size_t>(resolve_thread_count(0)));
}

// Where a call has a fixed cost, each round is one call, and the rounds fill calls of
// about that many configurations (a checker that counts each call as a GPU call).
TEST(TreePlanner, OneCallARoundWhereCallsCost) {
  Problem p(wall_with_a_hole());
  testing::CostlyCallChecker costly(*p.scene, 8192);
  TreePlanner planner(*p.scene, &costly, p.options(1));
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(*p.scene, result.path), "");
  const PlanGpuCalls& c = result.gpu_calls;
  EXPECT_EQ(c.total, costly.device_calls());
  EXPECT_EQ(c.total, c.edge_checks + c.shortcutting);
  EXPECT_EQ(c.state_checks + c.knn, 0u);
  // A call a round; the path is certified after shortcutting, with the tree path's edges
  // in the same calls (edge checks only where a shortened path failed).
  EXPECT_GE(c.edge_checks, result.rounds);
  EXPECT_LE(c.edge_checks, result.rounds + 20);
  EXPECT_GT(c.shortcutting, 0u);
  EXPECT_GE(planner.lanes(), 8u);
}

// Where calls cost, hard problems get larger rounds: about 4,096 rows a round in the first
// 8 rounds, then twice as many every 8 rounds, up to 32,768 (a closed wall: the trees
// never join, and every call is a round's); the stage times of rounds drawn beside a
// call add up to at most the plan's.
TEST(TreePlanner, RoundsGrowEveryEightRoundsWhereCallsCost) {
  Problem p(testing::kCubeAndThinWallScene);
  struct Recording : testing::CostlyCallChecker {
    using CostlyCallChecker::CostlyCallChecker;
    void check(const float* q, std::size_t n, std::uint8_t* verdicts) override {
      sizes.push_back(n);
      CostlyCallChecker::check(q, n, verdicts);
    }
    std::vector<std::size_t> sizes;
  } recording(*p.scene, 8192);
  constexpr std::size_t kRounds = 42;
  PlanOptions options = p.options(1);
  options.should_stop = [&] { return recording.sizes.size() >= kRounds; };
  TreePlanner planner(*p.scene, &recording, options);
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(planner.paths_refused(), 0u);
  ASSERT_EQ(recording.sizes.size(), kRounds);
  EXPECT_EQ(result.rounds, kRounds);
  // Each round's lanes come from the last round's rows per lane: the round's rows are
  // about the aim, not exactly it (the first round's 64 lanes aside).
  for (std::size_t r = 1; r < kRounds; ++r) {
    const double aim = 4096.0 * (1 << std::min<std::size_t>(r / 8, 3));
    EXPECT_GT(recording.sizes[r], 0.6 * aim) << "round " << r + 1;
    EXPECT_LT(recording.sizes[r], 1.6 * aim) << "round " << r + 1;
  }
  // From the ninth round each round is drawn beside the call before (the trees grow
  // freely on either side of the wall): the stages count that time once.
  EXPECT_GT(planner.rounds_drawn_ahead(), 0u);
  const PlanTimes& t = result.times;
  EXPECT_GT(t.knn, 0);
  EXPECT_LE(t.sampling + t.knn + t.edge_checks + t.shortcutting, t.total);
}

// Where the trees can hardly grow (the start and the goal each shut in a box a little
// larger than the cube: nearly every extension hits a side), a round adds fewer nodes
// than one for every six lanes, and no round is drawn ahead: the lag would cost such trees
// half their progress.
TEST(TreePlanner, RoundsAfterOnesThatAddFewNodesAreNotDrawnAhead) {
  // Six plates 2 cm thick about a centre, leaving 0.15 each way inside.
  const auto box_about = [](const char* name, double x) {
    std::string text;
    const double c = 0.16, size = 0.34;
    const double centres[6][3] = {{x - c, 0, 0}, {x + c, 0, 0}, {x, -c, 0},
                                  {x, c, 0},     {x, 0, -c},    {x, 0, c}};
    for (int i = 0; i < 6; ++i) {
      const double sx = i / 2 == 0 ? 0.02 : size, sy = i / 2 == 1 ? 0.02 : size,
                   sz = i / 2 == 2 ? 0.02 : size;
      text += "  - {name: " + std::string(name) + std::to_string(i) + ", box: [" +
              std::to_string(sx) + ", " + std::to_string(sy) + ", " + std::to_string(sz) +
              "], pose: {xyz: [" + std::to_string(centres[i][0]) + ", " +
              std::to_string(centres[i][1]) + ", " + std::to_string(centres[i][2]) + "]}}\n";
    }
    return text;
  };
  Problem p(testing::cube_scene("boxed_in", box_about("start", -1) + box_about("goal", 1)));
  testing::CostlyCallChecker costly(*p.scene, 8192);
  constexpr std::size_t kRounds = 20;
  PlanOptions options = p.options(1);
  options.should_stop = [&] { return costly.device_calls() >= kRounds; };
  TreePlanner planner(*p.scene, &costly, options);
  const PlanResult result = planner.solve(p.scene->start.data(), p.scene->goal.data());
  EXPECT_FALSE(result.solved);
  EXPECT_EQ(costly.device_calls(), kRounds);
  EXPECT_EQ(result.rounds, kRounds);
  // The trees grew by fewer nodes than a sixth of one round's lanes in all.
  EXPECT_LT(6 * (result.milestones - 2), planner.lanes());
  EXPECT_EQ(planner.rounds_drawn_ahead(), 0u);
}

// The CPU backend's checks per lane with early stops grow the same trees as one call of
// every row: the same path for the same seed and lanes, with the same rounds drawn ahead
// (beside the call, or before the host's checks).
TEST(TreePlanner, HostChecksWithEarlyStopsGrowTheSameTreesAsOneCall) {
  Problem p(wall_with_a_hole());
  PlanOptions options = p.options(5);
  options.tree_lanes = 8;
  options.shortcut_rounds = 0;
  TreePlanner on_host(*p.scene, p.checker.get(), options);
  const PlanResult host = on_host.solve(p.scene->start.data(), p.scene->goal.data());
  testing::CostlyCallChecker costly(*p.scene, 8192);
  TreePlanner one_call(*p.scene, &costly, options);
  const PlanResult in_calls = one_call.solve(p.scene->start.data(), p.scene->goal.data());
  ASSERT_TRUE(host.solved && in_calls.solved);
  EXPECT_EQ(host.path, in_calls.path);
  EXPECT_EQ(host.rounds, in_calls.rounds);
  EXPECT_EQ(host.milestones, in_calls.milestones);
  EXPECT_GT(on_host.rounds_drawn_ahead(), 0u);
  EXPECT_EQ(on_host.rounds_drawn_ahead(), one_call.rounds_drawn_ahead());
}

TEST(PlannerChoice, NamesAndParsing) {
  for (const PlannerKind kind :
       {PlannerKind::kAuto, PlannerKind::kLazyPrm, PlannerKind::kPrm, PlannerKind::kRrtConnect}) {
    PlannerKind parsed = PlannerKind::kPrm;
    ASSERT_TRUE(parse_planner(planner_name(kind), &parsed));
    EXPECT_EQ(parsed, kind);
  }
  PlannerKind unchanged = PlannerKind::kPrm;
  EXPECT_FALSE(parse_planner("RRTConnect", &unchanged));
  EXPECT_FALSE(parse_planner("", &unchanged));
  EXPECT_EQ(unchanged, PlannerKind::kPrm);
  EXPECT_FALSE(keeps_roadmap(PlannerKind::kRrtConnect));
  EXPECT_TRUE(keeps_roadmap(PlannerKind::kAuto));
}

struct ShippedScene {
  explicit ShippedScene(const std::string& name)
      : scene(load_scene(testing::project_root() + "/scenes/" + name)),
        checker(scene),
        neighbors(make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu")) {}
  Scene scene;
  CpuChecker checker;
  std::unique_ptr<NeighborFinder> neighbors;
};

// A rigid body flying free (the piano: a floating base, no joint) goes to lazy PRM; its
// path passes the re-check.
TEST(PlannerChoice, AutoTakesLazyPrmForARigidBody) {
  ShippedScene s("piano.yaml");
  PlanOptions options = plan_options(s.scene);
  options.seed = 1;
  ChosenPlanner planner(s.scene, &s.checker, s.neighbors.get(), PlannerKind::kAuto, false, options);
  EXPECT_EQ(planner.used(), PlannerKind::kLazyPrm);
  EXPECT_EQ(planner.reason(), "a rigid body flying free");
  ASSERT_NE(planner.roadmap_planner(), nullptr);
  const PlanResult result = planner.solve(s.scene.start.data(), s.scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(s.scene, result.path), "");
  EXPECT_GT(result.milestones, 2000u);  // the roadmap's
}

TEST(PlannerChoice, AutoTakesTheTreesForJointsAndLazyPrmForRoadmaps) {
  ShippedScene s("pr2_base_arm.yaml");
  PlanOptions options = plan_options(s.scene);
  options.seed = 1;
  ChosenPlanner trees(s.scene, &s.checker, s.neighbors.get(), PlannerKind::kAuto, false, options);
  EXPECT_EQ(trees.used(), PlannerKind::kRrtConnect);  // a planar base and 7 arm joints
  EXPECT_EQ(trees.roadmap_planner(), nullptr);
  const PlanResult result = trees.solve(s.scene.start.data(), s.scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(s.scene, result.path), "");
  ChosenPlanner roadmap(s.scene, &s.checker, s.neighbors.get(), PlannerKind::kAuto, true, options);
  EXPECT_EQ(roadmap.used(), PlannerKind::kLazyPrm);
  ASSERT_NE(roadmap.roadmap_planner(), nullptr);
  ChosenPlanner named(s.scene, &s.checker, nullptr, PlannerKind::kRrtConnect, false, options);
  EXPECT_EQ(named.roadmap_planner(), nullptr);
  EXPECT_EQ(named.reason(), "");
}

// MotionBenchMaker's bookshelf_small 0005: lazy PRM on the GPU found no path in 10 s
// (benchmarks/RESULTS.md, 5d49a88); the trees find one on the cpu backend.
TEST(TreePlanner, SolvesAShelfProblemLazyPrmDidNot) {
  const std::string data = testing::shared_data();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data (set GPLANNER_SHARED_DATA)";
  const std::string panda = data + "/motionbenchmaker/panda";
  const testing::ScratchFolder folder;
  const std::string file = folder.write(
      "shelf.yaml", "name: bookshelf_small_0005\nrobot:\n  urdf: " + panda +
                        "/robot/panda.urdf\n  srdf: " + panda + "/robot/panda.srdf\n  packages: " +
                        "{meshes: " + panda + "/robot/meshes}\nmoveit:\n  scene: " + panda +
                        "/problems/bookshelf_small_panda/scene0005.yaml\n  request: " + panda +
                        "/problems/bookshelf_small_panda/request0005.yaml\n");
  const Scene scene = load_scene(file);
  CpuChecker checker(scene);
  PlanOptions options = plan_options(scene);
  options.seed = 1;
  options.time_limit_s = 120;
  TreePlanner planner(scene, &checker, options);
  const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  ASSERT_TRUE(result.solved) << result.stop_reason;
  EXPECT_EQ(testing::path_problem(scene, result.path), "");
}

TEST(TreePlannerGpu, PathsPassTheRecheckOnTheGpuBackend) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  for (const char* name : {"pr2_base_arm.yaml", "humanoid.yaml"}) {
    const Scene scene = load_scene(testing::project_root() + "/scenes/" + name);
    std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, "gpu");
    for (unsigned long long seed = 1; seed <= 3; ++seed) {
      PlanOptions options = plan_options(scene);
      options.seed = seed;
      TreePlanner planner(scene, checker.get(), options);
      const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
      ASSERT_TRUE(result.solved) << name << " seed " << seed << ": " << result.stop_reason;
      EXPECT_EQ(testing::path_problem(scene, result.path), "") << name << " seed " << seed;
      EXPECT_GT(result.gpu_calls.edge_checks, 0u);
    }
  }
}

}  // namespace
}  // namespace gplanner
