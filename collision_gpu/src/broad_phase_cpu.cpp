// The sphere broad phase on one CPU thread: all pairs (the seed's sequential baseline) and
// sort-and-sweep, both with the pair rule of geometry/sphere_overlap.h.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "gplanner/collision_gpu/broad_phase.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"

namespace gplanner {

namespace {

struct MethodName {
  BroadPhaseMethod method;
  const char* name;
};
constexpr MethodName kMethodNames[] = {
    {BroadPhaseMethod::kCpuAllPairs, "cpu-all-pairs"},
    {BroadPhaseMethod::kCpuSortSweep, "cpu-sort-sweep"},
    {BroadPhaseMethod::kGpuAllPairs, "gpu-all-pairs"},
    {BroadPhaseMethod::kGpuSortSweep, "gpu-sort-sweep"},
    {BroadPhaseMethod::kGpuGrid, "gpu-grid"},
    {BroadPhaseMethod::kGpuLbvh, "gpu-lbvh"},
};

// The axis along which the centres spread most (largest variance; the lowest on ties).
int widest_axis(const SphereArrays& s) {
  double sum[3] = {0, 0, 0}, square[3] = {0, 0, 0};
  for (std::size_t i = 0; i < s.n; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double c = s.centers[3 * i + a];
      sum[a] += c;
      square[a] += c * c;
    }
  }
  int best = 0;
  double best_variance = -1;
  for (int a = 0; a < 3; ++a) {
    const double mean = sum[a] / double(s.n);
    const double variance = square[a] / double(s.n) - mean * mean;
    if (variance > best_variance) {
      best = a;
      best_variance = variance;
    }
  }
  return best;
}

}  // namespace

const char* broad_phase_method_name(BroadPhaseMethod method) {
  for (const MethodName& m : kMethodNames)
    if (m.method == method) return m.name;
  return "unknown";
}

bool parse_broad_phase_method(const std::string& name, BroadPhaseMethod* method) {
  for (const MethodName& m : kMethodNames) {
    if (name == m.name) {
      *method = m.method;
      return true;
    }
  }
  return false;
}

const std::vector<BroadPhaseMethod>& broad_phase_methods() {
  static const std::vector<BroadPhaseMethod> methods = {
      BroadPhaseMethod::kCpuAllPairs, BroadPhaseMethod::kCpuSortSweep,
      BroadPhaseMethod::kGpuAllPairs, BroadPhaseMethod::kGpuSortSweep,
      BroadPhaseMethod::kGpuGrid,     BroadPhaseMethod::kGpuLbvh};
  return methods;
}

bool is_gpu_method(BroadPhaseMethod method) {
  return method == BroadPhaseMethod::kGpuAllPairs || method == BroadPhaseMethod::kGpuSortSweep ||
         method == BroadPhaseMethod::kGpuGrid || method == BroadPhaseMethod::kGpuLbvh;
}

void check_spheres(const SphereArrays& s) {
  if (s.n >= (std::size_t(1) << 31)) {
    throw std::invalid_argument("broad phase: " + std::to_string(s.n) +
                                " spheres; at most 2^31 - 1 fit the pair indices");
  }
  if (s.n > 0 && (s.centers == nullptr || s.radii == nullptr))
    throw std::invalid_argument("broad phase: null centre or radius array for n > 0 spheres");
  for (std::size_t i = 0; i < s.n; ++i) {
    const float* c = s.centers + 3 * i;
    if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) ||
        !std::isfinite(s.radii[i]) || s.radii[i] < 0) {
      throw std::invalid_argument("broad phase: sphere " + std::to_string(i) +
                                  " has a centre or radius that is not finite, or a negative "
                                  "radius; give finite centres and radii of 0 or more");
    }
  }
}

void all_pairs_cpu(const SphereArrays& s, std::vector<SpherePair>* pairs) {
  check_spheres(s);
  pairs->clear();
  const float* c = s.centers;
  const float* r = s.radii;
  for (std::size_t i = 0; i < s.n; ++i) {
    const float xi = c[3 * i], yi = c[3 * i + 1], zi = c[3 * i + 2], ri = r[i];
    for (std::size_t j = i + 1; j < s.n; ++j) {
      if (geometry::spheres_overlap(xi, yi, zi, ri, c[3 * j], c[3 * j + 1], c[3 * j + 2], r[j]))
        pairs->push_back({std::uint32_t(i), std::uint32_t(j)});
    }
  }
}

void sort_sweep_cpu(const SphereArrays& s, std::vector<SpherePair>* pairs) {
  check_spheres(s);
  pairs->clear();
  if (s.n < 2) return;
  const int axis = widest_axis(s);
  struct Interval {
    float lo, hi;
    std::uint32_t id;
  };
  std::vector<Interval> intervals(s.n);  // shape [n], sorted by lo
  for (std::size_t i = 0; i < s.n; ++i) {
    const float c = s.centers[3 * i + axis];
    intervals[i] = {geometry::cull_low(c, s.radii[i]), geometry::cull_high(c, s.radii[i]),
                    std::uint32_t(i)};
  }
  std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) {
    return a.lo < b.lo || (a.lo == b.lo && a.id < b.id);
  });
  const float* c = s.centers;
  const float* r = s.radii;
  for (std::size_t k = 0; k < s.n; ++k) {
    const Interval& a = intervals[k];
    const float* ca = c + 3 * std::size_t(a.id);
    for (std::size_t m = k + 1; m < s.n && intervals[m].lo <= a.hi; ++m) {
      const std::uint32_t b = intervals[m].id;
      const float* cb = c + 3 * std::size_t(b);
      if (geometry::spheres_overlap(ca[0], ca[1], ca[2], r[a.id], cb[0], cb[1], cb[2], r[b]))
        pairs->push_back({std::min(a.id, b), std::max(a.id, b)});
    }
  }
}

void sort_pairs(std::vector<SpherePair>* pairs) { std::sort(pairs->begin(), pairs->end()); }

}  // namespace gplanner
