#pragma once
// Broad-phase collision detection of bounding spheres: given n spheres, every pair (i, j),
// i < j, that overlaps (touching included; the rule of geometry/sphere_overlap.h). All
// methods, on the CPU and on the GPU (gpu_broad_phase.h), return exactly the same pair
// set, in an order of their own; sort_pairs() puts one in the canonical order.
// Plain C++: no CUDA headers.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gplanner {

// Host arrays of n spheres.
struct SphereArrays {
  const float* centers = nullptr;  // shape [n, 3]
  const float* radii = nullptr;    // shape [n]
  std::size_t n = 0;
};

// Two overlapping spheres by index, i < j.
struct SpherePair {
  std::uint32_t i = 0;
  std::uint32_t j = 0;
  bool operator==(const SpherePair& o) const { return i == o.i && j == o.j; }
  bool operator<(const SpherePair& o) const { return i < o.i || (i == o.i && j < o.j); }
};

enum class BroadPhaseMethod {
  kCpuAllPairs,   // every pair in turn on one CPU thread: the seed's sequential baseline
  kCpuSortSweep,  // sweep and prune along the axis of largest variance, one CPU thread
  kGpuAllPairs,   // every pair on the GPU, tiled in shared memory: the seed's parallel method
  kGpuSortSweep,  // sweep and prune on the GPU: radix sort of the intervals, a sweep per sphere
  kGpuGrid,       // uniform grid (cells of the largest diameter) sorted by cell, 27 neighbours
  kGpuLbvh,       // linear BVH: Morton codes, Karras' radix tree, bottom-up boxes, a query per
                  // sphere (spheres of very different sizes)
};

// "cpu-all-pairs", "cpu-sort-sweep", "gpu-all-pairs", "gpu-sort-sweep", "gpu-grid",
// "gpu-lbvh".
const char* broad_phase_method_name(BroadPhaseMethod method);
// Parses one of the names above; false for anything else.
bool parse_broad_phase_method(const std::string& name, BroadPhaseMethod* method);
const std::vector<BroadPhaseMethod>& broad_phase_methods();  // all of them, in the order above
bool is_gpu_method(BroadPhaseMethod method);

// Throws std::invalid_argument naming the first bad sphere: a centre or radius that is not
// finite, a negative radius, null arrays with n > 0, or n of 2^31 spheres or more.
void check_spheres(const SphereArrays& spheres);

// The pairs of `spheres` into `pairs` (replacing what it held, keeping its capacity).
// all_pairs_cpu finds them in the canonical order; sort_sweep_cpu in an order of its own.
void all_pairs_cpu(const SphereArrays& spheres, std::vector<SpherePair>* pairs);
void sort_sweep_cpu(const SphereArrays& spheres, std::vector<SpherePair>* pairs);

// The canonical order: by i, then j.
void sort_pairs(std::vector<SpherePair>* pairs);

}  // namespace gplanner
