// Path shortcutting: a lazy PRM path shortened on checkers whose calls cost nothing,
// a few thousand samples and as much as many samples (as the GPU's do): every shortened path is
// free at a tenth of the edge resolution; checking the next round's shortcuts with this round's
// fine check gives the same path in fewer calls; checking every shortcut at both resolutions at
// once takes one call a round, for the same path. Certified shortcutting certifies the path its
// rounds give in one certification, and where that fails (a shortcut free at the samples, through
// an obstacle between them) runs the rounds again with every shortcut certified: the path it
// returns is certified either way. A shortcut that is the path itself (over the midpoints the
// rounds put in) is not checked, nor is one checked before.

#include "gplanner/planner/planning/path_shortcutting.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

using testing::CostlyCallChecker;

PlanOptions unshortened_options(const Scene& scene) {
  PlanOptions options = plan_options(scene);
  options.seed = 1;
  options.shortcut_rounds = 0;
  return options;
}

// Lazy PRM's path on `scene`, seed 1, not shortened: what the tests shorten.
PlanResult unshortened_path(const Scene& scene, CollisionChecker* checker) {
  std::unique_ptr<NeighborFinder> neighbors =
      make_neighbor_finder(make_metric(scene.space, scene.planner), "cpu");
  RoadmapPlanner planner(scene, checker, neighbors.get(), RoadmapStrategy::kLazyPrm,
                         unshortened_options(scene));
  return planner.solve(scene.start.data(), scene.goal.data());
}

TEST(PathShortcutting, FewerCallsWhereCallsCostMoreThanSamples) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  CpuChecker cpu(scene);
  const PlanOptions options = unshortened_options(scene);
  const PlanResult found = unshortened_path(scene, &cpu);
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
    LocalPlanner fine(scene, &checker, refined(options.local, options.final_check_refinement));
    paths[c] = found.path;
    std::mt19937_64 rng(1);
    const double length =
        shortcut_path(scene.space, &local, &fine, nullptr, rounds, candidates, &rng, &paths[c]);
    EXPECT_EQ(testing::path_problem(scene, paths[c]), "") << "call cost " << costs[c];
    EXPECT_LT(length, found.length);
    calls[c] = local.stats().batches + fine.stats().batches;
    if (c > 0) EXPECT_EQ(fine.stats().batches, 0u);  // every call through `local`
  }
  // Checking the next round's shortcuts early, or every shortcut at both resolutions at
  // once, changes nothing but the number of calls.
  EXPECT_EQ(paths[1], paths[0]);
  EXPECT_EQ(paths[2], paths[0]);
  EXPECT_LT(calls[1], calls[0]);
  EXPECT_LE(calls[2], static_cast<std::size_t>(rounds));  // one call a round
  EXPECT_LT(calls[2], calls[0]);
}

// Whether every segment of `path` is certified free (checked with a certifier of its own).
bool certified_whole(const Scene& scene, CollisionChecker* checker, const PlanOptions& options,
                     std::vector<float> path) {
  CertifiedMotions certify(scene, checker, options.certified);
  const int width = scene.space.width();
  const std::size_t segments = path.size() / width - 1;
  std::vector<std::uint8_t> invalid(segments);
  EXPECT_TRUE(certify.check_motions(path.data(), path.data() + width, segments, invalid.data()));
  return std::count(invalid.begin(), invalid.end(), 1) == 0;
}

TEST(PathShortcutting, CertifiedInOneCertificationOfTheShortenedPath) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  CpuChecker cpu(scene);
  const PlanOptions options = unshortened_options(scene);
  const PlanResult found = unshortened_path(scene, &cpu);
  ASSERT_TRUE(found.solved) << found.stop_reason;
  CostlyCallChecker checker(scene, 4096);
  LocalPlanner local(scene, &checker, options.local);
  LocalPlanner fine(scene, &checker, refined(options.local, options.final_check_refinement));
  CertifiedMotions certify(scene, &checker, options.certified);
  std::vector<float> path = found.path;
  std::mt19937_64 rng(1);
  const double length = shortcut_path(scene.space, &local, &fine, &certify, 6, 256, &rng, &path);
  EXPECT_LT(length, found.length);
  EXPECT_EQ(testing::path_problem(scene, path), "");
  EXPECT_TRUE(certified_whole(scene, &cpu, options, path));
  // One certification: of the returned path's segments, nothing else.
  EXPECT_EQ(certify.stats().motions, path.size() / scene.space.width() - 1);
}

// A unit cube flying from (-1, 0, 0) to (1, 0, 0) within [-2, 2] x [-2, 2] x [-1, 1],
// `obstacles` (a scene file's obstacles: section, or nothing) in its way.
Scene flying_cube_scene(const std::string& obstacles) {
  const testing::ScratchFolder folder;
  folder.write("cube.obj", testing::kCubeObj);
  return load_scene(folder.write("scene.yaml", R"(name: flying_cube
robot:
  mesh: cube.obj
)" + obstacles + R"(bounds:
  min: [-2, -2, -1]
  max: [2, 2, 1]
start:
  base: {xyz: [-1, 0, 0], quat_wxyz: [1, 0, 0, 0]}
goal:
  base: {xyz: [1, 0, 0], quat_wxyz: [1, 0, 0, 0]}
)"));
}

TEST(PathShortcutting, CertifiedWhereAShortcutPassesItsSamplesThroughAnObstacle) {
  const Scene scene = flying_cube_scene("obstacles:\n  - box: [0.5, 0.5, 0.5]\n");
  CpuChecker cpu(scene);
  PlanOptions options = plan_options(scene);
  // Checks with no sample inside a motion, only its ends: every shortcut passes them,
  // the straight line through the block too.
  LocalPlannerOptions blind = options.local;
  blind.resolution_fraction = 10;
  blind.max_displacement = 0;
  LocalPlanner local(scene, &cpu, blind), fine(scene, &cpu, blind);
  CertifiedMotions certify(scene, &cpu, options.certified);
  // Around the block: start, up, across, down, goal.
  std::vector<float> path;
  const float waypoints[5][2] = {{-1, 0}, {-1, 1}, {0, 1}, {1, 1}, {1, 0}};
  for (const auto& xy : waypoints) path.insert(path.end(), {xy[0], xy[1], 0, 1, 0, 0, 0});
  ASSERT_TRUE(certified_whole(scene, &cpu, options, path));
  const std::vector<float> around = path;
  std::mt19937_64 rng(1);
  shortcut_path(scene.space, &local, &fine, &certify, 3, 64, &rng, &path);
  // The straight line was taken by the rounds, failed its certification, and the rounds
  // ran again certifying each shortcut: what comes back is certified, and goes around.
  EXPECT_GT(certify.stats().motions, path.size() / scene.space.width() - 1);
  EXPECT_TRUE(certified_whole(scene, &cpu, options, path));
  for (std::size_t w = 0; w < path.size() / 7; ++w) EXPECT_FALSE(cpu.in_collision(&path[w * 7]));
}

// A checker that finds one configuration colliding (exactly that one: a thin obstacle
// that only one sample touches), every other free; its calls cost `per_call`.
class OneColliding : public CollisionChecker {
 public:
  OneColliding(std::vector<float> colliding, std::size_t per_call)
      : colliding_(std::move(colliding)), per_call_(per_call) {}
  std::string backend() const override { return "cpu"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override {
    const std::size_t width = colliding_.size();
    for (std::size_t i = 0; i < n; ++i) {
      verdicts[i] = std::equal(colliding_.begin(), colliding_.end(), configurations + i * width);
      colliding_checks_ += verdicts[i];
    }
    checked_ += n;
  }
  void check_clearances(const float* configurations, std::size_t n, const float*,
                        std::uint8_t* verdicts) override {
    check(configurations, n, verdicts);
  }
  std::size_t configurations_per_call_cost() const override { return per_call_; }
  std::size_t cheap_calls_up_to() const override { return 0; }
  // How many times the colliding configuration was checked; how many configurations were.
  std::size_t colliding_checks() const { return colliding_checks_; }
  std::size_t checked() const { return checked_; }

 private:
  std::vector<float> colliding_;
  std::size_t per_call_;
  std::size_t colliding_checks_ = 0, checked_ = 0;
};

// The flying cube's detour: start (-1, 0, 0), aside (-1, 0.5, 0), goal (goal_x, 0, 0),
// none turned.
std::vector<float> flying_cube_detour(float goal_x) {
  std::vector<float> path;
  for (const float y : {0.0f, 0.5f, 0.0f}) path.insert(path.end(), {-1, y, 0, 1, 0, 0, 0});
  path[path.size() - 7] = goal_x;
  return path;
}

TEST(PathShortcutting, ShortcutsCheckedAtOnceKeepTheirCoarseSamples) {
  // The flying cube, nothing in its way: a path of a detour (start, aside, goal) whose one
  // shortcut (start to goal) has a coarse sample that no fine sample matches. Where
  // that sample collides, the two stages (coarse, then fine) reject the shortcut; a
  // round that checks it at once at the fine resolution must too, whatever a call costs.
  const Scene scene = flying_cube_scene("");
  const PlanOptions options = plan_options(scene);
  const LocalPlannerOptions fine_options = refined(options.local, options.final_check_refinement);
  const int width = scene.space.width();
  std::vector<float> path = flying_cube_detour(-1);
  // The goal's x: one whose shortcut's fine segments are no multiple of its coarse ones.
  OneColliding probe({}, 0);
  LocalPlanner coarse_probe(scene, &probe, options.local), fine_probe(scene, &probe, fine_options);
  int coarse = 0, fine_count = 0;
  for (float x = 1; x > -0.5f; x -= 0.01f) {
    path[2 * width] = x;
    coarse = coarse_probe.segments(&path[0], &path[2 * width]);
    fine_count = fine_probe.segments(&path[0], &path[2 * width]);
    if (coarse >= 2 && fine_count % coarse != 0) break;
  }
  ASSERT_GE(coarse, 2);
  ASSERT_NE(fine_count % coarse, 0);
  std::vector<float> sample(width);
  scene.space.interpolate(&path[0], &path[2 * width], 1.0 / coarse, sample.data());
  for (const std::size_t per_call : {std::size_t(0), std::size_t(1) << 20}) {
    OneColliding checker(sample, per_call);
    LocalPlanner local(scene, &checker, options.local), fine(scene, &checker, fine_options);
    std::vector<float> shortened = path;
    std::mt19937_64 rng(1);
    shortcut_path(scene.space, &local, &fine, nullptr, 1, 64, &rng, &shortened);
    EXPECT_EQ(shortened, path) << "call cost " << per_call;
  }
}

TEST(PathShortcutting, AShortcutThatFailedIsNotCheckedAgain) {
  // The flying cube's detour (start, aside, goal) whose shortcut (start to goal) has a
  // fine sample that collides, no coarse one. The first round finds it free at the coarse
  // resolution, takes it, and finds it colliding at the fine one; the second round, on
  // the detour with midpoints, proposes the same motion again (start to goal): known, it
  // is not checked again. The colliding configuration is checked once, whatever a call
  // costs.
  const Scene scene = flying_cube_scene("");
  const PlanOptions options = plan_options(scene);
  const LocalPlannerOptions fine_options = refined(options.local, options.final_check_refinement);
  const int width = scene.space.width();
  const std::vector<float> path = flying_cube_detour(1);
  OneColliding probe({}, 0);
  LocalPlanner coarse_probe(scene, &probe, options.local), fine_probe(scene, &probe, fine_options);
  const int coarse = coarse_probe.segments(&path[0], &path[2 * width]);
  const int fine_count = fine_probe.segments(&path[0], &path[2 * width]);
  ASSERT_GE(coarse, 2);
  ASSERT_GT(fine_count, coarse);  // its first fine sample is none of the coarse ones
  std::vector<float> sample(width);
  scene.space.interpolate(&path[0], &path[2 * width], 1.0 / fine_count, sample.data());
  std::vector<float> straight(path.begin(), path.begin() + width);
  straight.insert(straight.end(), path.begin() + 2 * width, path.end());
  for (const std::size_t per_call : {std::size_t(0), std::size_t(4096)}) {
    OneColliding checker(sample, per_call);
    LocalPlanner local(scene, &checker, options.local), fine(scene, &checker, fine_options);
    std::vector<float> shortened = path;
    std::mt19937_64 rng(1);
    shortcut_path(scene.space, &local, &fine, nullptr, 2, 64, &rng, &shortened);
    EXPECT_EQ(checker.colliding_checks(), 1u) << "call cost " << per_call;
    EXPECT_GT(shortened.size(), straight.size()) << "call cost " << per_call;
  }
}

TEST(PathShortcutting, ShortcutsThatAreThePathItselfAreNotChecked) {
  // The flying cube's straight motion from start to goal, with the midpoint a round's
  // refinement puts in: the one shortcut (start to goal) is the motion the path already
  // is, no shorter. One round checks no configuration, at either resolution, whatever a
  // call costs, and leaves the path as it is. A waypoint a little off the midpoint makes
  // a shortcut that is checked and taken.
  const Scene scene = flying_cube_scene("");
  const PlanOptions options = plan_options(scene);
  const LocalPlannerOptions fine_options = refined(options.local, options.final_check_refinement);
  const int width = scene.space.width();
  const std::vector<float> start = {-1, 0, 0, 1, 0, 0, 0}, goal = {1, 0.5f, 0, 1, 0, 0, 0};
  std::vector<float> straight = start;
  straight.insert(straight.end(), goal.begin(), goal.end());
  std::vector<float> mid(width);
  scene.space.interpolate(start.data(), goal.data(), 0.5, mid.data());
  for (const float offset : {0.0f, 1e-3f}) {
    std::vector<float> path = start;
    path.insert(path.end(), mid.begin(), mid.end());
    path[width + 1] += offset;
    path.insert(path.end(), goal.begin(), goal.end());
    for (const std::size_t per_call : {std::size_t(0), std::size_t(4096)}) {
      // A configuration no motion here comes near: every one checked is free.
      OneColliding checker(std::vector<float>(width, 100.0f), per_call);
      LocalPlanner local(scene, &checker, options.local), fine(scene, &checker, fine_options);
      std::vector<float> shortened = path;
      std::mt19937_64 rng(1);
      shortcut_path(scene.space, &local, &fine, nullptr, 1, 64, &rng, &shortened);
      if (offset == 0) {
        EXPECT_EQ(shortened, path) << "call cost " << per_call;
        EXPECT_EQ(checker.checked(), 0u) << "call cost " << per_call;
      } else {
        EXPECT_EQ(shortened, straight) << "call cost " << per_call;
        EXPECT_GT(checker.checked(), 0u) << "call cost " << per_call;
      }
    }
  }
}

}  // namespace
}  // namespace gplanner
