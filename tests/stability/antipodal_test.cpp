// Stability: interpolation through antipodal rotations. q and -q are one rotation: the
// local planner's interpolation between them must stay there, not sweep a full turn;
// between near-antipodal quaternions (-q turned by a small angle) it must take the
// short way, the angle the planner's metric measures. An edge check between such
// states samples exactly what the metric says it spans: consecutive samples at most
// the resolution apart, and the samples FCL re-checks are the ones the check saw.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr double kPi = 3.14159265358979323846;
// How far the float metric's rotation angle, 2 acos |dot|, may lie from the true angle:
// the dot product of unit float quaternions rounds by up to about 2e-7, and acos near 1
// turns that into 2 sqrt(2 * 2e-7) = 1.3e-3 rad.
constexpr double kMetricAngleError = 1.5e-3;

Eigen::Quaterniond rotation_of(const float* q) {
  return Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized();
}

// The rotation angle between two rows' rotations, in double.
double angle_between(const float* a, const float* b) {
  return rotation_of(a).angularDistance(rotation_of(b));
}

// b: a's rotation turned by `angle` about a random axis, then negated (the same
// rotation written as the far quaternion); its position moved by `shift`.
std::vector<float> near_antipode(const float* a, double angle, const Eigen::Vector3d& shift,
                                 std::mt19937_64* rng) {
  std::normal_distribution<double> normal;
  const Eigen::Vector3d axis =
      Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)).normalized();
  const Eigen::Quaterniond turned =
      rotation_of(a) * Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
  std::vector<float> b(a, a + 7);
  for (int k = 0; k < 3; ++k) b[k] = static_cast<float>(a[k] + shift[k]);
  b[3] = static_cast<float>(-turned.w());
  b[4] = static_cast<float>(-turned.x());
  b[5] = static_cast<float>(-turned.y());
  b[6] = static_cast<float>(-turned.z());
  return b;
}

TEST(StabilityAntipodes, InterpolationTakesTheShortWayTheMetricMeasures) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/piano.yaml");
  ASSERT_EQ(scene.space.base, BaseType::kFloating);
  const ConfigurationMetric metric = make_metric(scene.space, scene.planner);
  auto checker = make_collision_checker(scene, "cpu");
  const LocalPlannerOptions options;
  LocalPlanner local(scene, checker.get(), options);
  const double step = options.resolution_fraction * kPi;  // the rotation's resolution
  std::mt19937_64 rng(41);
  float a[7], sample[7], previous[7];
  for (int trial = 0; trial < 200; ++trial) {
    scene.space.sample_uniform(&rng, a);
    for (const double angle : {0.0, 1e-6, 1e-3, 0.05, 0.5, 2.0, 3.0}) {
      const std::vector<float> b = near_antipode(a, angle, Eigen::Vector3d::Zero(), &rng);
      const double truth = angle_between(a, b.data());  // the short way, in double
      EXPECT_NEAR(truth, angle, 1e-5);
      // The metric measures the short way. It is float: acos of a dot product within
      // a few ulps of 1 reads angles below about 1e-3 rad as 0 (see kMetricAngleError).
      EXPECT_NEAR(quaternion_angle(a + 3, b.data() + 3), truth, kMetricAngleError) << angle;
      EXPECT_NEAR(distance(metric, a, b.data()), metric.rotation_weight * truth,
                  metric.rotation_weight * kMetricAngleError)
          << angle;
      // The edge is cut by that angle, as for the same end written as +q.
      std::vector<float> b_plus = b;
      for (int k = 3; k < 7; ++k) b_plus[k] = -b[k];
      const int segments = local.segments(a, b.data());
      EXPECT_EQ(segments, local.segments(a, b_plus.data())) << angle;
      EXPECT_LE(std::abs(segments - std::max(1, int(std::ceil(truth / step)))), 1) << angle;
      // Samples sweep the short arc once: monotone away from a, each step at most the
      // resolution, the whole sweep the metric's angle (not a full turn minus it).
      double swept = 0, last_from_a = 0;
      std::copy(a, a + 7, previous);
      for (int j = 1; j <= segments; ++j) {
        scene.space.interpolate(a, b.data(), double(j) / segments, sample);
        const double from_a = angle_between(a, sample), stride = angle_between(previous, sample);
        EXPECT_LE(stride, step + 1e-5) << "angle " << angle << ", sample " << j;
        EXPECT_GE(from_a, last_from_a - 1e-5) << "angle " << angle << ", sample " << j;
        EXPECT_LE(from_a, truth + 1e-5) << "angle " << angle << ", sample " << j;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(sample[k], a[k]);
        swept += stride;
        last_from_a = from_a;
        std::copy(sample, sample + 7, previous);
      }
      EXPECT_NEAR(swept, truth, 1e-4) << angle;
      EXPECT_NEAR(angle_between(sample, b.data()), 0, 1e-5) << angle;
    }
  }
}

// q to -q with the position moving: every sample keeps the rotation (no turn at all),
// and the edge is cut by the translation alone.
TEST(StabilityAntipodes, QToMinusQKeepsTheRotation) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/piano.yaml");
  auto checker = make_collision_checker(scene, "cpu");
  LocalPlanner local(scene, checker.get());
  std::mt19937_64 rng(43);
  float a[7], b[7], sample[7];
  for (int trial = 0; trial < 200; ++trial) {
    scene.space.sample_uniform(&rng, a);
    scene.space.sample_uniform(&rng, b);
    for (int k = 3; k < 7; ++k) b[k] = -a[k];
    LocalPlannerOptions pure;
    const int segments = local.segments(a, b);
    const double extent = (scene.space.base_max - scene.space.base_min).norm();
    const double shift = Eigen::Vector3d(b[0] - a[0], b[1] - a[1], b[2] - a[2]).norm();
    EXPECT_EQ(segments, std::max(1, int(std::ceil(shift / (pure.resolution_fraction * extent)))));
    for (int j = 0; j <= segments; ++j) {
      scene.space.interpolate(a, b, double(j) / segments, sample);
      EXPECT_LT(angle_between(a, sample), 1e-5) << "sample " << j << " of " << segments;
    }
  }
  // Not moving at all: one segment, nothing in between to check.
  for (int k = 0; k < 3; ++k) b[k] = a[k];
  EXPECT_EQ(local.segments(a, b), 1);
}

// Edges between near-antipodal ends in the piano's rooms, checked by the local planner
// on a backend; the same samples (j / segments of the way) re-checked by FCL one by
// one. An edge with a sample FCL finds colliding must be invalid; an edge found
// invalid must have a sample within the band of the obstacles.
void expect_edges_match_fcl(const std::string& backend) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/piano.yaml");
  auto checker = make_collision_checker(scene, backend);
  ASSERT_EQ(checker->backend(), backend);
  LocalPlanner local(scene, checker.get());
  FclChecker fcl(scene);
  const double delta = tolerance_delta(scene);
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> shift(-0.3, 0.3);
  const std::size_t count = 300, w = 7;
  std::vector<float> from(count * w), to(count * w);
  for (std::size_t e = 0; e < count; ++e) {
    scene.space.sample_uniform(&rng, &from[e * w]);
    const double angle = std::vector<double>{1e-3, 0.3, 1.5, 3.0}[e % 4];
    const std::vector<float> b = near_antipode(
        &from[e * w], angle, Eigen::Vector3d(shift(rng), shift(rng), shift(rng)), &rng);
    std::copy(b.begin(), b.end(), &to[e * w]);
  }
  std::vector<std::uint8_t> invalid(count);
  ASSERT_TRUE(local.check_motions(from.data(), to.data(), count, invalid.data()));
  std::size_t invalid_edges = 0;
  for (std::size_t e = 0; e < count; ++e) {
    const int segments = local.segments(&from[e * w], &to[e * w]);
    std::vector<float> samples((segments - 1) * w);
    for (int j = 1; j < segments; ++j)
      scene.space.interpolate(&from[e * w], &to[e * w], double(j) / segments,
                              &samples[(j - 1) * w]);
    std::vector<std::uint8_t> truth(segments - 1);
    fcl.check(samples.data(), segments - 1, truth.data());
    bool fcl_collides = false;
    for (const std::uint8_t t : truth) fcl_collides |= t != 0;
    if (fcl_collides) EXPECT_TRUE(invalid[e]) << backend << ": edge " << e << " missed";
    if (invalid[e] && !fcl_collides) {
      std::vector<double> distances(segments - 1);
      fcl.distance(samples.data(), segments - 1, distances.data());
      EXPECT_LT(*std::min_element(distances.begin(), distances.end()), delta)
          << backend << ": edge " << e << " invalid outside the band";
    }
    invalid_edges += invalid[e];
  }
  EXPECT_GT(invalid_edges, 0u);
  EXPECT_LT(invalid_edges, count);
}

TEST(StabilityAntipodes, EdgeChecksSampleWhatFclRechecksCpu) { expect_edges_match_fcl("cpu"); }

TEST(StabilityAntipodes, GpuEdgeChecksSampleWhatFclRechecks) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_edges_match_fcl("gpu");
}

}  // namespace
}  // namespace gplanner
