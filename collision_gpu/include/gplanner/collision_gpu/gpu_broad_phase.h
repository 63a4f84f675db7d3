#pragma once
// The sphere broad phase on the GPU (see broad_phase.h): all pairs (the seed's parallel
// method), sort-and-sweep, a uniform grid sorted by cell, and a linear BVH. One call is one
// frame: the spheres uploaded, the pairs found, the pairs downloaded. Plain C++: no CUDA
// headers.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/broad_phase.h"

namespace gplanner {

// Whether a GPU can be used here; when not, `reason` says why (no device, a build without
// CUDA).
bool gpu_broad_phase_available(std::string* reason = nullptr);

// What the last find_pairs() did.
struct GpuBroadPhaseStats {
  double milliseconds = 0;        // the call's time, spheres on the host to pairs on the host
  std::size_t pairs = 0;          // pairs found
  std::size_t pair_capacity = 0;  // the device pair buffer's size when the call ended
  int reruns = 0;                 // frames run again, the pair buffer having overflowed
  int kernels = 0;                // kernel launches (sorts counted as one)
  int sweep_axis = -1;            // gpu-sort-sweep: 0, 1 or 2 (the axis of largest variance)
  double cell_size = 0;           // gpu-grid: the cell's side
};

class GpuBroadPhase {
 public:
  // Throws std::runtime_error when no GPU can be used (or gplanner was built without
  // CUDA), saying why.
  GpuBroadPhase();
  ~GpuBroadPhase();
  GpuBroadPhase(const GpuBroadPhase&) = delete;
  GpuBroadPhase& operator=(const GpuBroadPhase&) = delete;

  // The pairs of `spheres` (host arrays) by a GPU method into `pairs` (host; replaced, in
  // an order of the method's own). When the pair buffer on the device overflows, it grows
  // to the exact count and the frame runs again: no pair is ever dropped. Throws
  // std::invalid_argument for a CPU method or bad spheres (check_spheres' rules, checked
  // on the device), std::runtime_error for a CUDA error or pairs beyond device memory.
  // Not thread safe: one call at a time per object.
  void find_pairs(BroadPhaseMethod method, const SphereArrays& spheres,
                  std::vector<SpherePair>* pairs);

  const GpuBroadPhaseStats& last_stats() const;
  std::string device_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner
