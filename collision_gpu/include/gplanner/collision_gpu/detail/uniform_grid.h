#pragma once
// The uniform grid of the sphere broad phase (gpu-grid), host and device: cells a little
// wider than the largest diameter, keyed x, then y, then z; the spheres sorted by key; each
// sphere's query for the later spheres of its 27 neighbouring cells. The tests build and
// query the same grid on the CPU, one sphere at a time.

#include <cmath>

#include "gplanner/collision_gpu/geometry/host_device.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"

namespace gplanner::detail::grid {

// Cells per axis at most (cells are widened where the spheres' spread needs more): cell
// coordinates 1 .. 2^20 + 1, and their neighbours, fit 21 bits; a key is 63 bits.
inline constexpr double kMaxCellsPerAxis = double(1 << 20);
inline constexpr int kCellBits = 21;
// Cells are this much wider than the largest diameter: a pair the rule accepts is at most
// (r_a + r_b)(1 + 4 2^-24) apart along an axis (plus geometry::kCullFloor where squares
// underflow), so it lies in neighbouring cells; cell coordinates are computed in double.
inline constexpr double kCellSlack = 1e-4;

// The lowest corner of the centres and the cell's side.
struct GridFrame {
  double origin[3];
  double cell;
};

// The grid of centres within [low, high] (per axis) and radii up to radius_max.
GP_HD GridFrame make_grid_frame(const float low[3], const float high[3], float radius_max) {
  GridFrame g{};
  double widest = 0;
  for (int a = 0; a < 3; ++a) {
    g.origin[a] = low[a];
    widest = ::fmax(widest, double(high[a]) - g.origin[a]);
  }
  g.cell = ::fmax(2 * double(radius_max) * (1 + kCellSlack) + 4 * geometry::kCullFloor,
                  widest / kMaxCellsPerAxis);
  if (!(g.cell > 0)) g.cell = 1;  // every sphere a point, all at one place
  return g;
}

GP_HD unsigned long long cell_key(unsigned x, unsigned y, unsigned z) {
  return (static_cast<unsigned long long>(x) << (2 * kCellBits)) |
         (static_cast<unsigned long long>(y) << kCellBits) | z;
}

// The key of the cell holding a centre, each coordinate from 1 (so that its neighbours are
// never below 0).
GP_HD unsigned long long cell_key_of(float x, float y, float z, const GridFrame& g) {
  const double inverse = 1.0 / g.cell;
  const float c[3] = {x, y, z};
  unsigned q[3];
  for (int a = 0; a < 3; ++a) {
    q[a] = 1u + static_cast<unsigned>(
                    ::fmin(::floor((double(c[a]) - g.origin[a]) * inverse), kMaxCellsPerAxis));
  }
  return cell_key(q[0], q[1], q[2]);
}

// The first position in [begin, n) whose key is not below `key`.
GP_HD unsigned lower_bound(const unsigned long long* keys, unsigned begin, unsigned n,
                           unsigned long long key) {
  unsigned end = n;
  while (begin < end) {
    const unsigned middle = begin + (end - begin) / 2;
    if (keys[middle] < key) {
      begin = middle + 1;
    } else {
      end = middle;
    }
  }
  return begin;
}

// The spheres at sorted positions after k, in the cells neighbouring k's, that overlap
// sphere k, each through emit(m). Keys order x, then y, then z, so the neighbours with keys
// not below k's are (x, y, z..z+1), (x, y+1, z-1..z+1) and (x+1, y-1..y+1, z-1..z+1): four
// runs of keys, each found by a binary search. Every overlapping pair is found once, from
// its earlier sphere.
template <typename Emit>
GP_HD void query_later(const float* spheres /* shape [n, 4] sorted by key */,
                       const unsigned long long* keys /* shape [n], sorted */, unsigned n,
                       unsigned k, Emit&& emit) {
  const float* a = spheres + 4 * static_cast<unsigned long long>(k);
  const unsigned long long key = keys[k];
  const unsigned mask = (1u << kCellBits) - 1;
  const unsigned x = unsigned(key >> (2 * kCellBits)), y = unsigned(key >> kCellBits) & mask,
                 z = unsigned(key) & mask;
  const auto run = [&](unsigned begin, unsigned long long last) {
    for (unsigned m = begin; m < n && keys[m] <= last; ++m) {
      const float* b = spheres + 4 * static_cast<unsigned long long>(m);
      if (geometry::spheres_overlap(a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3])) emit(m);
    }
  };
  run(k + 1, cell_key(x, y, z + 1));
  run(lower_bound(keys, k + 1, n, cell_key(x, y + 1, z - 1)), cell_key(x, y + 1, z + 1));
  for (unsigned dy = 0; dy < 3; ++dy) {
    run(lower_bound(keys, k + 1, n, cell_key(x + 1, y + dy - 1, z - 1)),
        cell_key(x + 1, y + dy - 1, z + 1));
  }
}

}  // namespace gplanner::detail::grid
