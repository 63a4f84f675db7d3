#pragma once
// Seeded sphere scenes for the broad-phase tests (CPU and GPU), and a double-precision
// O(n^2) reference.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "gplanner/collision_gpu/broad_phase.h"

namespace gplanner::testing {

struct SphereScene {
  std::vector<float> centers;  // shape [n, 3]
  std::vector<float> radii;    // shape [n]
  std::size_t size() const { return radii.size(); }
  SphereArrays arrays() const { return {centers.data(), radii.data(), radii.size()}; }
  void add(float x, float y, float z, float r) {
    centers.insert(centers.end(), {x, y, z});
    radii.push_back(r);
  }
};

// Centres uniform in a cube of side `side`, radii uniform in [r_min, r_max].
inline SphereScene uniform_spheres(std::size_t n, std::uint64_t seed, float side, float r_min,
                                   float r_max) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> c(0.f, side), r(r_min, r_max);
  SphereScene s;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = c(rng), y = c(rng), z = c(rng);
    s.add(x, y, z, r(rng));
  }
  return s;
}

// `clusters` tight Gaussian clusters far apart, radii in [0.05, 0.2].
inline SphereScene clustered_spheres(std::size_t n, std::uint64_t seed, int clusters) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> where(-100.f, 100.f), r(0.05f, 0.2f);
  std::normal_distribution<float> spread(0.f, 0.5f);
  std::vector<float> hubs;
  for (int k = 0; k < 3 * clusters; ++k) hubs.push_back(where(rng));
  SphereScene s;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = 3 * (i % std::size_t(clusters));
    const float x = hubs[k] + spread(rng), y = hubs[k + 1] + spread(rng),
                z = hubs[k + 2] + spread(rng);
    s.add(x, y, z, r(rng));
  }
  return s;
}

// Radii spread over four orders of magnitude (log-uniform in [1e-3, 10]).
inline SphereScene mixed_radii_spheres(std::size_t n, std::uint64_t seed, float side) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> c(0.f, side), e(-3.f, 1.f);
  SphereScene s;
  for (std::size_t i = 0; i < n; ++i) {
    const float x = c(rng), y = c(rng), z = c(rng);
    s.add(x, y, z, std::pow(10.f, e(rng)));
  }
  return s;
}

// An integer lattice (spacing 1) offset by `origin` with radius `radius`: with 0.5 every
// lattice neighbour touches exactly (|d| = 1 = r + r, all exact in float) and no
// diagonal one does; with less, nothing overlaps.
inline SphereScene lattice_spheres(int side, float origin, float radius) {
  SphereScene s;
  for (int x = 0; x < side; ++x)
    for (int y = 0; y < side; ++y)
      for (int z = 0; z < side; ++z)
        s.add(origin + float(x), origin + float(y), origin + float(z), radius);
  return s;
}

// The pairs in double precision; `near` gets the pairs within a relative 1e-5 of
// touching, where float and double may disagree.
inline std::vector<SpherePair> reference_pairs(const SphereScene& s,
                                               std::vector<SpherePair>* near = nullptr) {
  std::vector<SpherePair> pairs;
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      double d2 = 0, scale = 0;
      for (int a = 0; a < 3; ++a) {
        const double d = double(s.centers[3 * i + a]) - double(s.centers[3 * j + a]);
        d2 += d * d;
        scale = std::max({scale, std::fabs(double(s.centers[3 * i + a])),
                          std::fabs(double(s.centers[3 * j + a]))});
      }
      const double reach = double(s.radii[i]) + double(s.radii[j]);
      const SpherePair pair{std::uint32_t(i), std::uint32_t(j)};
      if (d2 <= reach * reach) pairs.push_back(pair);
      if (near && std::fabs(std::sqrt(d2) - reach) <= 1e-5 * (reach + scale) + 1e-20)
        near->push_back(pair);
    }
  }
  return pairs;
}

}  // namespace gplanner::testing
