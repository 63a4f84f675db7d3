// The uniform grid's core (detail/uniform_grid.h), built and queried on the CPU one sphere
// at a time as the GPU does it in parallel: exactly the all-pairs pair set.

#include "gplanner/collision_gpu/detail/uniform_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "collision_gpu/sphere_scenes.h"

namespace gplanner {
namespace {

std::vector<SpherePair> grid_pairs(const testing::SphereScene& s, double* cell = nullptr) {
  const unsigned n = unsigned(s.size());
  std::vector<SpherePair> pairs;
  if (n < 2) return pairs;
  float low[3] = {1e30f, 1e30f, 1e30f}, high[3] = {-1e30f, -1e30f, -1e30f}, radius = 0;
  for (unsigned i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], s.centers[3 * i + a]);
      high[a] = std::max(high[a], s.centers[3 * i + a]);
    }
    radius = std::max(radius, s.radii[i]);
  }
  const detail::grid::GridFrame g = detail::grid::make_grid_frame(low, high, radius);
  if (cell) *cell = g.cell;
  std::vector<unsigned long long> keys(n);
  for (unsigned i = 0; i < n; ++i)
    keys[i] =
        detail::grid::cell_key_of(s.centers[3 * i], s.centers[3 * i + 1], s.centers[3 * i + 2], g);
  std::vector<unsigned> ids(n);
  std::iota(ids.begin(), ids.end(), 0u);
  std::stable_sort(ids.begin(), ids.end(),
                   [&](unsigned a, unsigned b) { return keys[a] < keys[b]; });
  std::vector<unsigned long long> sorted_keys;
  std::vector<float> sorted;  // shape [n, 4]
  for (const unsigned i : ids) {
    sorted_keys.push_back(keys[i]);
    sorted.insert(sorted.end(),
                  {s.centers[3 * i], s.centers[3 * i + 1], s.centers[3 * i + 2], s.radii[i]});
  }
  for (unsigned k = 0; k < n; ++k) {
    detail::grid::query_later(sorted.data(), sorted_keys.data(), n, k, [&](unsigned m) {
      pairs.push_back({std::min(ids[k], ids[m]), std::max(ids[k], ids[m])});
    });
  }
  sort_pairs(&pairs);
  return pairs;
}

void expect_all_pairs(const testing::SphereScene& s) {
  std::vector<SpherePair> expected;
  all_pairs_cpu(s.arrays(), &expected);
  const std::vector<SpherePair> found = grid_pairs(s);
  EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << "a pair twice";
  EXPECT_EQ(found, expected);
}

TEST(BroadPhaseGrid, PairsMatchAllPairs) {
  testing::SphereScene two;
  two.add(0, 0, 0, 1);
  two.add(2, 0, 0, 1);
  expect_all_pairs(two);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    expect_all_pairs(testing::uniform_spheres(1500, seed, 20.f, 0.2f, 0.6f));
    expect_all_pairs(testing::clustered_spheres(1000, seed + 3, 4));
    expect_all_pairs(testing::mixed_radii_spheres(1000, seed + 6, 50.f));
  }
  expect_all_pairs(testing::uniform_spheres(400, 9, 1.f, 2.f, 3.f));  // all overlap
  for (const float origin : {0.f, -3.f, 1000.f, 65536.f})
    expect_all_pairs(testing::lattice_spheres(8, origin, 0.5f));
  testing::SphereScene points;  // one cell; a point whose square underflows
  for (int i = 0; i < 50; ++i) points.add(1.f, 2.f, 3.f, 0.f);
  points.add(1e-30f, 0.f, 0.f, 0.f);
  points.add(0.f, 0.f, 0.f, 0.f);
  expect_all_pairs(points);
}

// Tiny spheres spread far apart: cells are widened so that at most 2^20 span an axis.
TEST(BroadPhaseGrid, CellsWidenForAWideSpread) {
  testing::SphereScene s = testing::uniform_spheres(500, 11, 1e6f, 1e-4f, 1e-3f);
  s.add(5e5f, 5e5f, 5e5f, 1e-3f);
  s.add(5e5f + 1.5e-3f, 5e5f, 5e5f, 1e-3f);  // a pair well inside one widened cell
  double cell = 0;
  grid_pairs(s, &cell);
  EXPECT_GE(cell, 1e6 / detail::grid::kMaxCellsPerAxis * 0.99);
  expect_all_pairs(s);
}

}  // namespace
}  // namespace gplanner
