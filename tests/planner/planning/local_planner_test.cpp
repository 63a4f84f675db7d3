// Local planning: sample order, resolution, the displacement bound, and batched motion
// checks against checking every sample one by one.

#include "gplanner/planner/planning/local_planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/planning/motion_bound.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/forward_kinematics.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/scenes/" + name);
}

TEST(CoarseToFineOrder, VisitsEveryInteriorSampleOnceMidpointFirst) {
  for (int n : {1, 2, 3, 4, 7, 8, 100, 129}) {
    const std::vector<int> order = coarse_to_fine_order(n);
    ASSERT_EQ(order.size(), static_cast<std::size_t>(std::max(0, n - 1))) << n;
    const std::set<int> unique(order.begin(), order.end());
    EXPECT_EQ(unique.size(), order.size()) << n;
    if (n >= 2) {
      EXPECT_EQ(*unique.begin(), 1);
      EXPECT_EQ(*unique.rbegin(), n - 1);
      EXPECT_EQ(order.front(), n / 2);
    }
  }
  // The first three of 8 segments: 4, then 2 and 6.
  const std::vector<int> eight = coarse_to_fine_order(8);
  EXPECT_EQ(std::vector<int>(eight.begin(), eight.begin() + 3), (std::vector<int>{4, 2, 6}));
}

TEST(LocalPlanner, SegmentsStepEveryComponentByOnePercentOfItsExtent) {
  const Scene scene = load("piano.yaml");
  CpuChecker checker(scene);
  LocalPlanner local(scene, &checker);
  const double diagonal = (scene.space.base_max - scene.space.base_min).norm();
  const std::vector<float> q = testing::sample_configurations(scene, 200, 3);
  const int w = scene.space.width();
  const float* start = scene.start.data();
  std::vector<float> moved(start, start + w);
  // A translation only: 1% of the bounds' diagonal per segment.
  moved[0] += static_cast<float>(0.2 * diagonal);
  EXPECT_NEAR(local.segments(start, moved.data()), 20, 1);
  // A rotation only, by 90 degrees about z: a half turn is 100 segments.
  std::vector<float> turned(start, start + w);
  const Eigen::Quaterniond r =
      Eigen::Quaterniond(start[3], start[4], start[5], start[6]) *
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  turned[3] = r.w(), turned[4] = r.x(), turned[5] = r.y(), turned[6] = r.z();
  EXPECT_NEAR(local.segments(start, turned.data()), 50, 1);
  EXPECT_EQ(local.segments(&q[0], &q[0]), 1);
  for (int i = 0; i + 1 < 200; i += 2) EXPECT_GE(local.segments(&q[i * w], &q[(i + 1) * w]), 1);
}

// The straight-line motion sampled at every interior point, one configuration at a time.
std::vector<std::uint8_t> check_one_by_one(const Scene& scene, CollisionChecker* checker,
                                           const LocalPlanner& local, const std::vector<float>& a,
                                           const std::vector<float>& b, std::size_t count) {
  const int w = scene.space.width();
  std::vector<std::uint8_t> invalid(count, 0);
  std::vector<float> q(w);
  for (std::size_t e = 0; e < count; ++e) {
    const int n = local.segments(&a[e * w], &b[e * w]);
    for (int j = 1; j < n && !invalid[e]; ++j) {
      scene.space.interpolate(&a[e * w], &b[e * w], static_cast<double>(j) / n, q.data());
      invalid[e] = checker->in_collision(q.data()) ? 1 : 0;
    }
  }
  return invalid;
}

void expect_batched_equals_one_by_one(const std::string& scene_name, double scale) {
  const Scene scene = load(scene_name);
  CpuChecker checker(scene);
  const int w = scene.space.width();
  // Motions between free configurations and free configurations nearby (scaled toward
  // them), so that some are valid and some are not.
  const std::vector<float> pool = testing::sample_configurations(scene, 4000, 11);
  std::vector<std::uint8_t> verdicts(4000);
  checker.check(pool.data(), pool.size() / w, verdicts.data());
  std::vector<float> a, b, mid(w);
  for (std::size_t i = 0; i + 1 < 4000; i += 2) {
    if (verdicts[i] || verdicts[i + 1]) continue;
    scene.space.interpolate(&pool[i * w], &pool[(i + 1) * w], scale, mid.data());
    a.insert(a.end(), &pool[i * w], &pool[i * w] + w);
    b.insert(b.end(), mid.begin(), mid.end());
  }
  const std::size_t count = a.size() / w;
  ASSERT_GT(count, 10u) << scene_name;
  LocalPlannerOptions small_batches;
  small_batches.one_batch_samples = 16;  // force the level-by-level path
  small_batches.max_batch_samples = 64;
  LocalPlanner staged(scene, &checker, small_batches);
  std::vector<std::uint8_t> invalid(count);
  staged.check_motions(a.data(), b.data(), count, invalid.data());
  const std::vector<std::uint8_t> expected = check_one_by_one(scene, &checker, staged, a, b, count);
  EXPECT_EQ(invalid, expected) << scene_name;
  std::size_t bad = std::count(invalid.begin(), invalid.end(), 1);
  EXPECT_GT(bad, 0u) << scene_name;
  EXPECT_LT(bad, count) << scene_name;
  EXPECT_GE(staged.stats().batches, 2u);  // level by level
  // One batch gives the same verdicts.
  LocalPlanner whole(scene, &checker);
  std::vector<std::uint8_t> again(count);
  whole.check_motions(a.data(), b.data(), count, again.data());
  EXPECT_EQ(again, expected) << scene_name;
  EXPECT_LE(staged.stats().samples, whole.stats().samples);
}

TEST(LocalPlanner, BatchedChecksEqualCheckingEverySampleRigid) {
  expect_batched_equals_one_by_one("piano.yaml", 0.05);
}

TEST(LocalPlanner, BatchedChecksEqualCheckingEverySampleArticulated) {
  expect_batched_equals_one_by_one("pr2_base_arm.yaml", 0.3);
}

// Levels of at least least_level_samples (a planner's own checks on the CPU backends, so
// that every call gives the host's threads work): the same verdicts in fewer calls, each
// (but a last) of at least that many samples; a few motions left take more samples each.
TEST(LocalPlanner, LeastLevelSamplesGiveTheSameVerdictsInFewerCalls) {
  const Scene scene = load("pr2_base_arm.yaml");
  CpuChecker checker(scene);
  const int w = scene.space.width();
  const std::vector<float> pool = testing::sample_configurations(scene, 2000, 17);
  std::vector<std::uint8_t> verdicts(2000);
  checker.check(pool.data(), 2000, verdicts.data());
  std::vector<float> a, b, mid(w);
  for (std::size_t i = 0; i + 1 < 2000; i += 2) {
    if (verdicts[i] || verdicts[i + 1]) continue;
    scene.space.interpolate(&pool[i * w], &pool[(i + 1) * w], 0.3, mid.data());
    a.insert(a.end(), &pool[i * w], &pool[i * w] + w);
    b.insert(b.end(), mid.begin(), mid.end());
  }
  const std::size_t count = a.size() / w;
  ASSERT_GT(count, 10u);
  for (const std::size_t motions : {count, std::size_t(3)}) {  // many motions, and a few
    SCOPED_TRACE(motions);
    LocalPlannerOptions leveled;
    leveled.least_level_samples = 256;
    LocalPlanner plain(scene, &checker), full_levels(scene, &checker, leveled);
    std::vector<std::uint8_t> expected(motions), invalid(motions);
    plain.check_motions(a.data(), b.data(), motions, expected.data());
    full_levels.check_motions(a.data(), b.data(), motions, invalid.data());
    EXPECT_EQ(invalid, expected);
    EXPECT_EQ(invalid, check_one_by_one(scene, &checker, plain, a, b, motions));
    EXPECT_LT(full_levels.stats().batches, plain.stats().batches);
    EXPECT_GE(full_levels.stats().samples, 256 * (full_levels.stats().batches - 1));
  }
}

// Where calls cost as much as many samples, a first call of the coarsest samples of
// every motion finds most invalid motions: the same verdicts from fewer samples, in two
// calls where one would hold them all.
TEST(LocalPlanner, AProbeCallFindsMostInvalidMotionsFirst) {
  const Scene scene = load("pr2_base_arm.yaml");
  const int w = scene.space.width();
  const std::vector<float> pool = testing::sample_configurations(scene, 400, 13);
  const std::size_t count = 200;  // motions across the space: most collide somewhere
  std::vector<float> a(pool.begin(), pool.begin() + count * w),
      b(pool.begin() + count * w, pool.end());
  testing::CostlyCallChecker one_call(scene, 0);  // no probe: every sample in one call
  testing::CostlyCallChecker costly_calls(scene, 1024);
  LocalPlanner plain(scene, &one_call), probing(scene, &costly_calls);
  std::vector<std::uint8_t> expected(count), invalid(count);
  plain.check_motions(a.data(), b.data(), count, expected.data());
  probing.check_motions(a.data(), b.data(), count, invalid.data());
  EXPECT_EQ(invalid, expected);
  const std::size_t bad = std::count(expected.begin(), expected.end(), 1);
  EXPECT_GT(bad, count / 2);
  EXPECT_LT(bad, count);
  ASSERT_GT(plain.stats().samples, 2 * 1024u) << "too few samples for a probe";
  EXPECT_EQ(plain.stats().batches, 1u);
  EXPECT_EQ(probing.stats().batches, 2u);
  EXPECT_LT(probing.stats().samples, plain.stats().samples / 2);
}

// A stop ends a large call (a PRM round's every edge) before any sample is checked, and
// it says so; the same call without the stop checks them.
TEST(LocalPlanner, AStopEndsALargeCallBeforeAnySample) {
  const Scene scene = load("piano.yaml");
  CpuChecker checker(scene);
  const int w = scene.space.width();
  const std::size_t count = 200000;
  std::vector<float> a(count * w), b(count * w);
  std::mt19937_64 rng(3);
  for (std::size_t i = 0; i < count; ++i) {
    scene.space.sample_uniform(&rng, &a[i * w]);
    scene.space.sample_uniform(&rng, &b[i * w]);
  }
  std::vector<std::uint8_t> invalid(count);
  LocalPlanner stopped(scene, &checker);
  int asked = 0;
  stopped.set_stop([&asked] { return ++asked > 0; });
  EXPECT_FALSE(stopped.check_motions(a.data(), b.data(), count, invalid.data()));
  EXPECT_GT(asked, 0);
  EXPECT_EQ(stopped.stats().samples, 0u);
  LocalPlanner going(scene, &checker);
  going.set_stop([] { return false; });
  EXPECT_TRUE(going.check_motions(a.data(), b.data(), 1000, invalid.data()));
  EXPECT_GT(going.stats().samples, 0u);
}

TEST(LocalPlanner, LastValidFractionStopsBeforeTheFirstCollision) {
  const Scene scene = load("piano.yaml");
  CpuChecker checker(scene);
  LocalPlanner local(scene, &checker);
  // The scene's straight line from start to goal collides.
  const double f = local.last_valid_fraction(scene.start.data(), scene.goal.data());
  EXPECT_GT(f, 0.0);
  EXPECT_LT(f, 1.0);
  const int n = local.segments(scene.start.data(), scene.goal.data());
  const int w = scene.space.width();
  std::vector<float> q(w);
  for (int j = 1; j <= static_cast<int>(std::lround(f * n)); ++j) {
    scene.space.interpolate(scene.start.data(), scene.goal.data(), double(j) / n, q.data());
    EXPECT_FALSE(checker.in_collision(q.data())) << j;
  }
  scene.space.interpolate(scene.start.data(), scene.goal.data(), f + 1.0 / n, q.data());
  EXPECT_TRUE(checker.in_collision(q.data()));
}

// Largest distance any vertex of the robot moves between configurations a and b.
double vertex_motion(const Scene& scene, const float* a, const float* b) {
  const RobotModel& robot = scene.robot;
  std::vector<double> pa(robot.joints.size()), pb(robot.joints.size());
  scene.space.joint_positions(robot, a, pa.data());
  scene.space.joint_positions(robot, b, pb.data());
  std::vector<Eigen::Isometry3d> Xa, Xb;
  forward_kinematics(robot, scene.space.base_pose(a), pa.data(), &Xa);
  forward_kinematics(robot, scene.space.base_pose(b), pb.data(), &Xb);
  double most = 0;
  for (std::size_t l = 0; l < robot.links.size(); ++l)
    for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
      most = std::max(most, (Xa[l] * p - Xb[l] * p).norm());
  return most;
}

TEST(MotionBound, BoundsEveryVertexMotion) {
  for (const char* name : {"piano.yaml", "humanoid.yaml", "pr2_reach.yaml", "pr2_base_arm.yaml"}) {
    const Scene scene = load(name);
    const MotionBound bound(scene.robot, scene.space);
    const int w = scene.space.width();
    const std::vector<float> q = testing::sample_configurations(scene, 60, 5);
    std::vector<float> near(w);
    double tightest = 1e9;
    for (int i = 0; i + 1 < 60; i += 2) {
      // Whole motions, and short ones (where the bound matters for sampling).
      for (double t : {1.0, 0.02}) {
        scene.space.interpolate(&q[i * w], &q[(i + 1) * w], t, near.data());
        const double actual = vertex_motion(scene, &q[i * w], near.data());
        const double b = bound.displacement(&q[i * w], near.data());
        EXPECT_GE(b, actual * (1 - 1e-6)) << name;
        if (actual > 0) tightest = std::min(tightest, b / actual);
      }
    }
    EXPECT_LT(tightest, 20.0) << name << ": the bound should not be wildly loose";
  }
}

// Per link, how far its points move, in the world and relative to every ancestor link.
TEST(MotionBound, LinkDisplacementsBoundEveryLinksMotion) {
  for (const char* name : {"piano.yaml", "humanoid.yaml", "pr2_reach.yaml", "pr2_base_arm.yaml"}) {
    const Scene scene = load(name);
    const RobotModel& robot = scene.robot;
    const MotionBound bound(robot, scene.space);
    const int w = scene.space.width();
    const std::size_t links = robot.links.size();
    const std::vector<float> q = testing::sample_configurations(scene, 40, 7);
    std::vector<float> near(w);
    std::vector<double> moved(links), pa(robot.joints.size()), pb(robot.joints.size());
    std::size_t tested = 0, relative_tight = 0;
    for (int i = 0; i + 1 < 40; i += 2) {
      for (double t : {1.0, 0.05}) {
        scene.space.interpolate(&q[i * w], &q[(i + 1) * w], t, near.data());
        bound.link_displacements(&q[i * w], near.data(), moved.data());
        EXPECT_LE(*std::max_element(moved.begin(), moved.end()),
                  bound.displacement(&q[i * w], near.data()) * (1 + 1e-9))
            << name;
        std::vector<Eigen::Isometry3d> Xa, Xb;
        scene.space.joint_positions(robot, &q[i * w], pa.data());
        scene.space.joint_positions(robot, near.data(), pb.data());
        forward_kinematics(robot, scene.space.base_pose(&q[i * w]), pa.data(), &Xa);
        forward_kinematics(robot, scene.space.base_pose(near.data()), pb.data(), &Xb);
        for (std::size_t l = 0; l < links; ++l) {
          // Every ancestor h of l (l itself, then up to the root).
          for (int h = static_cast<int>(l);;) {
            double most = 0;
            for (const Eigen::Vector3d& p : robot.links[l].collision.vertices) {
              const Eigen::Vector3d at_a = Xa[h].inverse() * (Xa[l] * p);
              const Eigen::Vector3d at_b = Xb[h].inverse() * (Xb[l] * p);
              most = std::max(most, (at_a - at_b).norm());
            }
            const double allowed = moved[l] - (h == static_cast<int>(l) ? 0.0 : moved[h]);
            if (h != static_cast<int>(l)) {
              EXPECT_LE(most, allowed * (1 + 1e-6) + 1e-9) << name << " link " << l << " in " << h;
              relative_tight += allowed < moved[l] * 0.999;
            }
            ++tested;
            if (robot.links[h].parent_joint < 0) break;
            h = robot.joints[robot.links[h].parent_joint].parent_link;
          }
          double world = 0;
          for (const Eigen::Vector3d& p : robot.links[l].collision.vertices)
            world = std::max(world, (Xa[l] * p - Xb[l] * p).norm());
          EXPECT_LE(world, moved[l] * (1 + 1e-6) + 1e-9) << name << " link " << l;
        }
      }
    }
    EXPECT_GT(tested, 0u);
    if (links > 1) EXPECT_GT(relative_tight, 0u) << name << ": relative bounds no tighter";
  }
}

TEST(RobotModel, DeepestCommonLink) {
  const Scene scene = load("pr2_reach.yaml");
  const RobotModel& robot = scene.robot;
  for (const auto& [a, b] : robot.checked_pairs()) {
    const int h = robot.deepest_common_link(a, b);
    // h is an ancestor of both (or one of them), and no child of h is.
    const auto ancestors = [&](int l) {
      std::vector<int> chain{l};
      while (robot.links[l].parent_joint >= 0)
        chain.push_back(l = robot.joints[robot.links[l].parent_joint].parent_link);
      return chain;
    };
    const std::vector<int> of_a = ancestors(a), of_b = ancestors(b);
    const auto position_a = std::find(of_a.begin(), of_a.end(), h);
    const auto position_b = std::find(of_b.begin(), of_b.end(), h);
    ASSERT_NE(position_a, of_a.end());
    ASSERT_NE(position_b, of_b.end());
    if (position_a != of_a.begin() && position_b != of_b.begin())
      EXPECT_NE(*(position_a - 1), *(position_b - 1)) << "a deeper common link exists";
  }
}

TEST(LocalPlanner, MaxDisplacementSetsTheSamples) {
  const Scene scene = load("pr2_base_arm.yaml");
  CpuChecker checker(scene);
  LocalPlannerOptions options;
  options.max_displacement = 0.01;
  LocalPlanner local(scene, &checker, options);
  const MotionBound bound(scene.robot, scene.space);
  const std::vector<float> q = testing::sample_configurations(scene, 20, 9);
  const int w = scene.space.width();
  for (int i = 0; i + 1 < 20; i += 2) {
    const int n = local.segments(&q[i * w], &q[(i + 1) * w]);
    EXPECT_EQ(n, std::max(1, static_cast<int>(std::ceil(
                                 bound.displacement(&q[i * w], &q[(i + 1) * w]) / 0.01))));
  }
}

}  // namespace
}  // namespace gplanner
