// Stability: configurations that mean the same pose must get the same verdict on every
// backend: a quaternion scaled away from unit length, its antipode (-q), and a
// continuous joint a full turn either way.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr float kTwoPi = 6.28318530717958647692f;

Scene load(const std::string& name) {
  return load_scene(testing::project_root() + "/scenes/" + name);
}

std::vector<float> sample(const Scene& scene, std::size_t n, unsigned seed) {
  std::vector<float> q(n * scene.space.width());
  std::mt19937_64 rng(seed);
  for (std::size_t i = 0; i < n; ++i) scene.space.sample_uniform(&rng, &q[i * scene.space.width()]);
  return q;
}

std::vector<std::uint8_t> verdicts(CollisionChecker* checker, const std::vector<float>& q,
                                   std::size_t n) {
  std::vector<std::uint8_t> v(n);
  checker->check(q.data(), n, v.data());
  return v;
}

void expect_quaternion_forms_agree(const std::string& backend) {
  const Scene scene = load("piano.yaml");
  const std::size_t n = 2000, w = scene.space.width();
  const std::vector<float> q = sample(scene, n, 5);
  std::vector<float> scaled = q, antipodal = q;
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 3; k < 7; ++k) {
      scaled[i * w + k] *= (i % 2 ? 3.0f : 0.25f);  // far from unit length either way
      antipodal[i * w + k] = -q[i * w + k];
    }
  }
  auto checker = make_collision_checker(scene, backend);
  ASSERT_EQ(checker->backend(), backend);
  const std::vector<std::uint8_t> base = verdicts(checker.get(), q, n);
  EXPECT_EQ(verdicts(checker.get(), scaled, n), base) << backend << ": non-unit quaternions";
  EXPECT_EQ(verdicts(checker.get(), antipodal, n), base) << backend << ": -q";
  std::size_t hits = 0;
  for (const std::uint8_t v : base) hits += v;
  EXPECT_GT(hits, 0u);
  EXPECT_LT(hits, n);
}

void expect_continuous_joints_wrap(const std::string& backend) {
  const Scene scene = load("pr2_base_arm.yaml");
  const std::size_t n = 1000, w = scene.space.width();
  std::vector<int> continuous;  // row entries of continuous joints (and the planar angle)
  continuous.push_back(2);
  for (std::size_t j = 0; j < scene.space.planned_joints.size(); ++j)
    if (scene.space.continuous[j]) continuous.push_back(scene.space.base_width() + j);
  ASSERT_GT(continuous.size(), 1u) << "the scene should plan a continuous joint";
  const std::vector<float> q = sample(scene, n, 9);
  std::vector<float> up = q, down = q;
  for (std::size_t i = 0; i < n; ++i) {
    for (const int k : continuous) {
      up[i * w + k] += kTwoPi;
      down[i * w + k] -= kTwoPi;
    }
  }
  auto checker = make_collision_checker(scene, backend);
  ASSERT_EQ(checker->backend(), backend);
  const std::vector<std::uint8_t> base = verdicts(checker.get(), q, n);
  // A full turn in float moves a value by up to half an ulp of 2 pi: a sample on the
  // band's edge may flip. Count rather than demand identity.
  const std::vector<std::uint8_t> a = verdicts(checker.get(), up, n),
                                  b = verdicts(checker.get(), down, n);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < n; ++i) differ += (a[i] != base[i]) + (b[i] != base[i]);
  EXPECT_LE(differ, 2u) << backend;
}

TEST(StabilityConfigurations, QuaternionFormsAgreeCpuAndFcl) {
  for (const char* backend : {"cpu", "fcl"}) expect_quaternion_forms_agree(backend);
}

TEST(StabilityConfigurations, ContinuousJointsWrapCpuAndFcl) {
  for (const char* backend : {"cpu", "fcl"}) expect_continuous_joints_wrap(backend);
}

TEST(StabilityConfigurations, GpuAgreesOnQuaternionFormsAndWraps) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_quaternion_forms_agree("gpu");
  expect_continuous_joints_wrap("gpu");
}

}  // namespace
}  // namespace gplanner
