// The sphere broad phase on the CPU: all pairs and sort-and-sweep return exactly the same
// pair set, and the one a double-precision reference gives (up to pairs within rounding
// of touching), on seeded scenes and on touching cases built to be exact.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "collision_gpu/sphere_scenes.h"
#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"

namespace gplanner {
namespace {

using testing::SphereScene;

std::vector<SpherePair> cpu_pairs(BroadPhaseMethod method, const SphereScene& scene) {
  std::vector<SpherePair> pairs;
  if (method == BroadPhaseMethod::kCpuAllPairs) {
    all_pairs_cpu(scene.arrays(), &pairs);
  } else {
    sort_sweep_cpu(scene.arrays(), &pairs);
  }
  return pairs;
}

// Both CPU methods against each other (exactly) and against the double reference (up to
// pairs within rounding of touching); returns the pair count.
std::size_t expect_exact_pairs(const SphereScene& scene) {
  std::vector<SpherePair> all = cpu_pairs(BroadPhaseMethod::kCpuAllPairs, scene);
  EXPECT_TRUE(std::is_sorted(all.begin(), all.end())) << "all pairs comes in canonical order";
  std::vector<SpherePair> sweep = cpu_pairs(BroadPhaseMethod::kCpuSortSweep, scene);
  sort_pairs(&sweep);
  EXPECT_EQ(all, sweep) << "sort-and-sweep differs from all pairs";
  for (const SpherePair& p : all) EXPECT_LT(p.i, p.j);
  EXPECT_TRUE(std::adjacent_find(all.begin(), all.end()) == all.end()) << "a pair twice";

  std::vector<SpherePair> near;
  const std::vector<SpherePair> reference = testing::reference_pairs(scene, &near);
  std::vector<SpherePair> differ;
  std::set_symmetric_difference(all.begin(), all.end(), reference.begin(), reference.end(),
                                std::back_inserter(differ));
  for (const SpherePair& p : differ) {
    EXPECT_TRUE(std::binary_search(near.begin(), near.end(), p))
        << "pair " << p.i << " " << p.j << " differs from the double reference, not near touching";
  }
  return all.size();
}

TEST(BroadPhase, MethodNamesRoundTrip) {
  for (const BroadPhaseMethod method : broad_phase_methods()) {
    BroadPhaseMethod parsed{};
    ASSERT_TRUE(parse_broad_phase_method(broad_phase_method_name(method), &parsed));
    EXPECT_EQ(parsed, method);
  }
  BroadPhaseMethod parsed{};
  EXPECT_FALSE(parse_broad_phase_method("gpu-octree", &parsed));
  EXPECT_EQ(broad_phase_methods().size(), 6u);
  EXPECT_TRUE(is_gpu_method(BroadPhaseMethod::kGpuGrid));
  EXPECT_FALSE(is_gpu_method(BroadPhaseMethod::kCpuSortSweep));
}

TEST(BroadPhase, NoneOneAndTwoSpheres) {
  SphereScene scene;
  EXPECT_EQ(expect_exact_pairs(scene), 0u);
  scene.add(0, 0, 0, 1);
  EXPECT_EQ(expect_exact_pairs(scene), 0u);
  scene.add(2, 0, 0, 1);  // touching: 2 = 1 + 1
  EXPECT_EQ(expect_exact_pairs(scene), 1u);
  scene.radii[1] = 0.5f;  // apart
  EXPECT_EQ(expect_exact_pairs(scene), 0u);
}

TEST(BroadPhase, UniformScenes) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    EXPECT_GT(expect_exact_pairs(testing::uniform_spheres(1500, seed, 20.f, 0.2f, 0.6f)), 100u);
    expect_exact_pairs(testing::uniform_spheres(700, seed + 10, 100.f, 0.f, 0.5f));
  }
}

TEST(BroadPhase, ClusteredAndMixedRadii) {
  EXPECT_GT(expect_exact_pairs(testing::clustered_spheres(1500, 4, 5)), 1000u);
  EXPECT_GT(expect_exact_pairs(testing::mixed_radii_spheres(1500, 5, 50.f)), 100u);
}

TEST(BroadPhase, AllOverlappingAndNoneOverlapping) {
  const std::size_t n = 600;
  EXPECT_EQ(expect_exact_pairs(testing::uniform_spheres(n, 6, 1.f, 2.f, 3.f)), n * (n - 1) / 2);
  EXPECT_EQ(expect_exact_pairs(testing::lattice_spheres(9, 0.f, 0.49f)), 0u);
}

// Lattice neighbours touch exactly: 3 * s^2 * (s - 1) pairs, near the origin and far from
// it (where an interval's ends round).
TEST(BroadPhase, TouchingLatticeIsExact) {
  const int s = 8;
  const std::size_t touching = 3u * s * s * (s - 1);
  for (const float origin : {0.f, -3.f, 1000.f, 65536.f}) {
    SCOPED_TRACE(origin);
    const SphereScene scene = testing::lattice_spheres(s, origin, 0.5f);
    EXPECT_EQ(expect_exact_pairs(scene), touching);
    EXPECT_EQ(testing::reference_pairs(scene).size(), touching);
  }
}

// Equal centres, zero radii and spheres one float step apart.
TEST(BroadPhase, EqualCoordinatesAndPoints) {
  SphereScene scene;
  for (int i = 0; i < 5; ++i) scene.add(1.f, 2.f, 3.f, 0.f);  // one point five times
  scene.add(std::nextafter(1.f, 2.f), 2.f, 3.f, 0.f);         // a step away: apart
  scene.add(10.f, 10.f, 10.f, 0.f);
  scene.add(10.f, 10.f, 10.f, 1.f);
  scene.add(1e-30f, 0.f, 0.f, 0.f);  // the square underflows: 0 <= 0
  scene.add(0.f, 0.f, 0.f, 0.f);
  EXPECT_EQ(expect_exact_pairs(scene), 10u + 1u + 1u);
}

TEST(BroadPhase, PairRuleIsInclusiveAndSymmetric) {
  EXPECT_TRUE(geometry::spheres_overlap(0, 0, 0, 1, 2, 0, 0, 1));
  EXPECT_TRUE(geometry::spheres_overlap(0, 0, 0, 0.5f, 0, 3, 4, 4.5f));  // 3-4-5
  EXPECT_FALSE(geometry::spheres_overlap(0, 0, 0, 0.5f, 0, 3, 4, std::nextafter(4.5f, 0.f)));
  EXPECT_EQ(geometry::spheres_overlap(0.1f, 0.2f, 0.3f, 0.25f, 0.4f, 0.1f, 0.2f, 0.1f),
            geometry::spheres_overlap(0.4f, 0.1f, 0.2f, 0.1f, 0.1f, 0.2f, 0.3f, 0.25f));
  // The culling interval contains the sphere's own extent.
  EXPECT_LE(geometry::cull_low(1e6f, 1e-3f), 1e6f - 1e-3f);
  EXPECT_GE(geometry::cull_high(1e6f, 1e-3f), 1e6f + 1e-3f);
}

TEST(BroadPhase, RefusesBadSpheres) {
  std::vector<SpherePair> pairs;
  for (const float bad :
       {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    SphereScene scene = testing::uniform_spheres(10, 7, 1.f, 0.1f, 0.2f);
    scene.centers[3 * 4 + 1] = bad;
    EXPECT_THROW(all_pairs_cpu(scene.arrays(), &pairs), std::invalid_argument);
    EXPECT_THROW(sort_sweep_cpu(scene.arrays(), &pairs), std::invalid_argument);
  }
  SphereScene scene = testing::uniform_spheres(10, 7, 1.f, 0.1f, 0.2f);
  scene.radii[3] = -0.1f;
  try {
    all_pairs_cpu(scene.arrays(), &pairs);
    FAIL() << "a negative radius was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sphere 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(all_pairs_cpu({nullptr, nullptr, 3}, &pairs), std::invalid_argument);
}

}  // namespace
}  // namespace gplanner
