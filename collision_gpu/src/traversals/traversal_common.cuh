#pragma once
// What the traversal kernels share on the device (CUDA translation units only): the
// full warp mask, the sum of a warp's test counts, launch sizes and error checks.

#include <cuda_runtime.h>

#include <cstddef>

#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/common/cuda_memory.cuh"

namespace gplanner::traversals {

constexpr unsigned kFullMask = 0xffffffffu;

inline void check_cuda(cudaError_t status, const char* what) { cuda::check(status, "CUDA", what); }

using cuda::blocks_for;

// The BV-pair and triangle tests of a batch on the device, added to by every warp
// through add_counts. Alone on its cache lines: many warps add to it at once.
struct alignas(128) DeviceTestCounts {
  unsigned long long bv_tests;
  unsigned long long triangle_tests;
};

// Adds this thread's counts to d_counts, one atomic per warp (all 32 lanes call it).
__device__ inline void add_counts(const detail::TraversalCounts& counts,
                                  DeviceTestCounts* d_counts) {
  unsigned long long bv = counts.bv_tests, tri = counts.triangle_tests;
  for (int offset = 16; offset > 0; offset /= 2) {
    bv += __shfl_down_sync(kFullMask, bv, offset);
    tri += __shfl_down_sync(kFullMask, tri, offset);
  }
  if ((threadIdx.x & 31) == 0) {
    atomicAdd(&d_counts->bv_tests, bv);
    atomicAdd(&d_counts->triangle_tests, tri);
  }
}

}  // namespace gplanner::traversals
