// Stability: narrow passages whose clearance is known by construction
// (tests/stability/scenes/generate.py): the real piano through a doorway 4 mm wider than
// its least width, and a peg into a hole 0.6 mm wider than the peg. Each plate is four
// boxes around a rectangular hole. Every case measures the clearance from the meshes
// (the hole between the boxes against the robot's extent at its start or goal
// orientation) and checks that the checkers' tolerance band delta (1e-5 of the scene's
// diagonal: 55 um for the piano, 3.2 um for the peg) is at least 20 times below the
// clearance a side (2 mm, 0.3 mm), so that the band cannot close the passage. Then it
// plans (lazy PRM, seeded, with each scene's planner settings: bridge-test sampling,
// rotations about the start's and goal's, edges bounded by robot-point motion), re-checks
// the path with FCL at a tenth of the edge resolution, and follows it finely to see it
// really go through the hole: from one side of the plate to the other (the piano) or
// into it (the peg), straddling the plate, inside the hole. The *Gpu* case plans the
// piano on the GPU (checker and k-NN), asserting that the GPU ran.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/configuration_space.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "planner/scene_test_support.h"
#include "test_support.h"

namespace gplanner {
namespace {

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/tests/stability/scenes/" + name);
}

// The plate: its extent along its normal, and the hole through it along the axes
// across (the gap between the boxes on either side of the origin).
struct Plate {
  int normal = 1;  // axis: y for the doorway's wall, z for the peg's plate
  double lo = 0, hi = 0;
  Eigen::AlignedBox3d hole;  // only the two axes across are meaningful
};

Plate plate_of(const Scene& scene, int normal) {
  Plate plate;
  plate.normal = normal;
  Eigen::AlignedBox3d all;
  for (int a = 0; a < 3; ++a) {
    plate.hole.min()[a] = -std::numeric_limits<double>::infinity();
    plate.hole.max()[a] = std::numeric_limits<double>::infinity();
  }
  for (const Obstacle& o : scene.obstacles) {
    const Eigen::AlignedBox3d box = o.mesh_S.bounds();
    all.extend(box);
    for (int a = 0; a < 3; ++a) {
      if (a == normal) continue;
      if (box.max()[a] < 0) plate.hole.min()[a] = std::max(plate.hole.min()[a], box.max()[a]);
      if (box.min()[a] > 0) plate.hole.max()[a] = std::min(plate.hole.max()[a], box.min()[a]);
    }
  }
  plate.lo = all.min()[normal];
  plate.hi = all.max()[normal];
  return plate;
}

// The robot's vertices placed at configuration q (shape: [width]), and their box.
Eigen::AlignedBox3d robot_box(const Scene& scene, const float* q) {
  const Eigen::Isometry3d X = scene.space.base_pose(q);
  Eigen::AlignedBox3d box;
  for (const Link& link : scene.robot.links)
    for (const Eigen::Vector3d& p : link.collision.vertices) box.extend(X * p);
  return box;
}

// Total clearance across axis a: the hole's width less the robot's extent at q.
double clearance(const Scene& scene, const Plate& plate, const float* q, int a) {
  const Eigen::AlignedBox3d box = robot_box(scene, q);
  return plate.hole.sizes()[a] - box.sizes()[a];
}

struct Passage {
  const char* file;
  int normal;                   // the plate's normal axis
  double min_total, max_total;  // the clearance the fixture promises, per axis across
  bool through;                 // the goal lies beyond the plate (else in the hole)
};

const Passage kPianoDoorway{"piano_doorway.yaml", 1, 0.003, 0.005, true};
const Passage kPegInHole{"peg_in_hole.yaml", 2, 0.0001, 0.001, false};

// The clearance from the meshes, against the band; returns the clearance a side.
double expect_clearance_above_band(const Scene& scene, const Passage& passage) {
  const Plate plate = plate_of(scene, passage.normal);
  // The orientation that passes: the goal's (the piano's start is the same).
  const float* q = scene.goal.data();
  double least = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (a == passage.normal) continue;
    const double total = clearance(scene, plate, q, a);
    least = std::min(least, total);
    std::cout << passage.file << ": " << 1000 * total << " mm to spare across axis " << a << "\n";
  }
  EXPECT_GE(least, passage.min_total) << passage.file;
  EXPECT_LE(least, passage.max_total) << passage.file;
  const double delta = tolerance_delta(scene);
  std::cout << passage.file << ": delta " << 1e6 * delta << " um, " << 0.5 * least / delta
            << " times below the clearance a side\n";
  EXPECT_LT(20 * delta, 0.5 * least) << passage.file << ": the band is not far below the clearance";
  return 0.5 * least;
}

// The path (shape [waypoints, width]) followed finely must go through the hole: it
// starts on one side of the plate and ends beyond it (the piano) or in it (the peg);
// some configuration straddles the plate (the robot out on both sides of it, or in it
// from above); and wherever the robot reaches into the plate, every robot vertex within
// the plate's thickness lies inside the hole's outline (a test on the geometry alone,
// apart from any checker's). Returns the least room between those vertices and the hole's
// sides.
double expect_through_the_hole(const Scene& scene, const Passage& passage,
                               const std::vector<float>& path) {
  const Plate plate = plate_of(scene, passage.normal);
  const int width = scene.space.width(), n = passage.normal;
  const std::size_t m = path.size() / width;
  const Eigen::AlignedBox3d start = robot_box(scene, scene.start.data());
  const Eigen::AlignedBox3d goal = robot_box(scene, scene.goal.data());
  const bool before = start.max()[n] < plate.lo;  // the start's side: below lo, or above hi
  EXPECT_TRUE(before || start.min()[n] > plate.hi) << "the start lies off the plate";
  if (passage.through) {
    EXPECT_TRUE(before ? goal.min()[n] > plate.hi : goal.max()[n] < plate.lo)
        << "the goal lies beyond the plate";
  }
  std::size_t straddling = 0, inside = 0;
  double room = std::numeric_limits<double>::infinity();
  std::vector<float> q(width);
  for (std::size_t i = 0; i + 1 < m; ++i) {
    for (int s = 0; s < 200; ++s) {
      scene.space.interpolate(&path[i * width], &path[(i + 1) * width], s / 200.0, q.data());
      const Eigen::AlignedBox3d box = robot_box(scene, q.data());
      if (box.max()[n] <= plate.lo || box.min()[n] >= plate.hi) continue;
      ++inside;
      const bool out_before = before ? box.min()[n] < plate.lo : box.max()[n] > plate.hi;
      const bool out_beyond = before ? box.max()[n] > plate.hi : box.min()[n] < plate.lo;
      straddling += out_before && (out_beyond || !passage.through);
      const Eigen::Isometry3d X = scene.space.base_pose(q.data());
      for (const Link& link : scene.robot.links) {
        for (const Eigen::Vector3d& v : link.collision.vertices) {
          const Eigen::Vector3d p = X * v;
          if (p[n] <= plate.lo || p[n] >= plate.hi) continue;
          for (int a = 0; a < 3; ++a) {
            if (a == n) continue;
            room = std::min({room, p[a] - plate.hole.min()[a], plate.hole.max()[a] - p[a]});
          }
        }
      }
    }
  }
  EXPECT_GT(straddling, 0u) << passage.file << ": the path never went through the plate";
  EXPECT_GE(room, 0) << passage.file << ": a robot vertex inside the plate, off the hole";
  std::cout << passage.file << ": " << inside
            << " of the path's fine samples reach into the plate, " << straddling
            << " straddle it; least room to a side there " << 1000 * room << " mm\n";
  return room;
}

PlanResult plan(const Scene& scene, const std::string& backend, unsigned long long seed) {
  std::unique_ptr<CollisionChecker> checker = make_collision_checker(scene, backend);
  EXPECT_EQ(checker->backend(), backend) << "no silent fallback";
  const std::unique_ptr<NeighborFinder> neighbors =
      make_neighbor_finder(make_metric(scene.space, scene.planner), backend);
  PlanOptions options = plan_options(scene);
  options.seed = seed;
  options.time_limit_s = 120;
  RoadmapPlanner planner(scene, checker.get(), neighbors.get(), RoadmapStrategy::kLazyPrm, options);
  const PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  std::cout << scene.name << " (" << backend << ", seed " << seed
            << "): " << (result.solved ? "solved" : result.stop_reason) << " in "
            << result.times.total << " s; " << result.milestones << " milestones, "
            << result.states_checked << " states and " << result.samples_checked
            << " edge samples checked, " << result.rounds << " rounds; length " << result.length
            << "\n";
  return result;
}

void expect_plans_through(const Passage& passage, const std::string& backend,
                          unsigned long long seed) {
  const Scene scene = load(passage.file);
  expect_clearance_above_band(scene, passage);
  const PlanResult result = plan(scene, backend, seed);
  ASSERT_TRUE(result.solved) << passage.file << ": " << result.stop_reason;
  EXPECT_EQ(testing::path_problem(scene, result.path), "") << passage.file;
  expect_through_the_hole(scene, passage, result.path);
}

TEST(StabilityNarrowPassages, PianoThroughA4MillimetreDoorwayCpu) {
  expect_plans_through(kPianoDoorway, "cpu", 1);
}

TEST(StabilityNarrowPassages, PegIntoAHoleWith06MillimetreClearanceCpu) {
  expect_plans_through(kPegInHole, "cpu", 1);
}

TEST(StabilityNarrowPassages, GpuPlansThePianoAndThePegThrough) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_plans_through(kPianoDoorway, "gpu", 1);
  expect_plans_through(kPegInHole, "gpu", 1);
}

}  // namespace
}  // namespace gplanner
