#pragma once
// Device code of the GPU sphere broad phase (gpu_broad_phase.cu launches it): packing and
// checking the spheres with their extents, the all-pairs tiles, the sort-and-sweep, the
// uniform grid and the linear BVH. Every method decides a pair with
// geometry::spheres_overlap; the culling (sweep intervals, grid cells, BVH boxes) is
// conservative by construction (geometry::cull_low/cull_high, cells wider than any
// overlapping pair's reach).

#include <cooperative_groups.h>
#include <cuda_runtime.h>

#include <cstdint>
#include <cstring>

#include "gplanner/collision_gpu/detail/lbvh.h"
#include "gplanner/collision_gpu/detail/uniform_grid.h"
#include "gplanner/collision_gpu/geometry/sphere_overlap.h"

namespace gplanner::detail::broad_phase {

namespace cg = cooperative_groups;

constexpr int kBlock = 256;
constexpr unsigned long long kNoBadSphere = ~0ull;

// A float's bits, ordered as the floats are (for atomicMin/Max and radix sort keys).
__device__ __forceinline__ unsigned ordered_bits(float f) {
  const unsigned u = __float_as_uint(f);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
__host__ __device__ inline float from_ordered_bits(unsigned u) {
  const unsigned bits = (u & 0x80000000u) ? (u & 0x7fffffffu) : ~u;
#if defined(__CUDA_ARCH__)
  return __uint_as_float(bits);
#else
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
#endif
}

// What one frame accumulates on the device; the host reads it back once, at the end.
struct FrameState {
  double sum[3];             // of the centres, per axis
  double square[3];          // of the centres' squares, per axis
  unsigned low[3];           // ordered bits of the smallest centre coordinate, per axis
  unsigned high[3];          // ... of the largest
  unsigned radius_max;       // ordered bits of the largest radius
  unsigned long long pairs;  // pairs found (may exceed the buffer: then run again)
  unsigned long long bad;    // the first sphere that is not finite, or kNoBadSphere
};

// Where the pairs go: a buffer of `capacity` and an atomic counter of all found.
struct PairOutput {
  uint2* pairs;  // shape [capacity]: (i, j), i < j
  unsigned long long capacity;
  unsigned long long* count;
};

// One slot per pair, reserved by one atomic per group of threads that found one together.
__device__ __forceinline__ void emit_pair(const PairOutput& out, unsigned a, unsigned b) {
  const cg::coalesced_group group = cg::coalesced_threads();
  unsigned long long base = 0;
  if (group.thread_rank() == 0) base = atomicAdd(out.count, (unsigned long long)group.size());
  const unsigned long long slot = group.shfl(base, 0) + group.thread_rank();
  if (slot < out.capacity) out.pairs[slot] = make_uint2(min(a, b), max(a, b));
}

__device__ __forceinline__ bool overlap(float4 a, float4 b) {
  return geometry::spheres_overlap(a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w);
}

template <typename T>
__device__ __forceinline__ T warp_sum(T v) {
  for (int offset = 16; offset > 0; offset /= 2) v += __shfl_down_sync(0xffffffffu, v, offset);
  return v;
}
__device__ __forceinline__ unsigned warp_min(unsigned v) {
  for (int offset = 16; offset > 0; offset /= 2)
    v = min(v, __shfl_down_sync(0xffffffffu, v, offset));
  return v;
}
__device__ __forceinline__ unsigned warp_max(unsigned v) {
  for (int offset = 16; offset > 0; offset /= 2)
    v = max(v, __shfl_down_sync(0xffffffffu, v, offset));
  return v;
}

// A sphere the broad phase takes: finite, with a radius of 0 or more.
__device__ __forceinline__ bool valid_sphere(float4 s) {
  return isfinite(s.x) && isfinite(s.y) && isfinite(s.z) && isfinite(s.w) && s.w >= 0.f;
}

__device__ __forceinline__ float4 load_sphere(const float* centers, const float* radii,
                                              unsigned i) {
  const float* c = centers + 3 * std::size_t(i);
  return make_float4(c[0], c[1], c[2], radii[i]);
}

// Packs centres [n, 3] and radii [n] into spheres [n] (x, y, z, r) and accumulates the
// centres' sums, squares and bounds and the largest radius. A sphere that is not valid is
// recorded (the smallest index) and replaced by a point at the origin, so that the rest
// of the frame stays well defined (the frame is then refused).
__global__ void pack_kernel(const float* centers, const float* radii, unsigned n, float4* spheres,
                            FrameState* frame) {
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  float4 s = make_float4(0.f, 0.f, 0.f, 0.f);
  const bool valid = i < n;
  if (valid) {
    s = load_sphere(centers, radii, i);
    if (!valid_sphere(s)) {
      atomicMin(&frame->bad, (unsigned long long)i);
      s = make_float4(0.f, 0.f, 0.f, 0.f);
    }
    spheres[i] = s;
  }
  const float c[3] = {s.x, s.y, s.z};
  const bool lane0 = (threadIdx.x & 31) == 0;
  for (int a = 0; a < 3; ++a) {
    const double sum = warp_sum(valid ? double(c[a]) : 0.0);
    const double square = warp_sum(valid ? double(c[a]) * double(c[a]) : 0.0);
    const unsigned low = warp_min(valid ? ordered_bits(c[a]) : ~0u);
    const unsigned high = warp_max(valid ? ordered_bits(c[a]) : 0u);
    if (lane0) {
      atomicAdd(&frame->sum[a], sum);
      atomicAdd(&frame->square[a], square);
      atomicMin(&frame->low[a], low);
      atomicMax(&frame->high[a], high);
    }
  }
  const unsigned radius = warp_max(valid ? ordered_bits(s.w) : 0u);
  if (lane0) atomicMax(&frame->radius_max, radius);
}

// All pairs, tiled, straight from the upload: block (bi, bj), bj >= bi, tests its 256
// spheres i of tile bi against the 256 spheres j of tile bj held in shared memory, j > i.
// The diagonal blocks check their tile's spheres (a frame with an invalid one is refused,
// whatever pairs it gave).
__global__ void all_pairs_kernel(const float* centers, const float* radii, unsigned n,
                                 FrameState* frame, PairOutput out) {
  const unsigned bi = blockIdx.x, bj = blockIdx.y;
  if (bj < bi) return;
  __shared__ float4 tile[kBlock];
  const unsigned j0 = bj * kBlock;
  if (j0 + threadIdx.x < n) {
    const float4 s = load_sphere(centers, radii, j0 + threadIdx.x);
    tile[threadIdx.x] = s;
    if (bi == bj && !valid_sphere(s))
      atomicMin(&frame->bad, (unsigned long long)(j0 + threadIdx.x));
  }
  __syncthreads();
  const unsigned i = bi * kBlock + threadIdx.x;
  if (i >= n) return;
  const float4 a = bi == bj ? tile[threadIdx.x] : load_sphere(centers, radii, i);
  const unsigned end = min(unsigned(kBlock), n - j0);
  for (unsigned t = bi == bj ? threadIdx.x + 1 : 0; t < end; ++t) {
    if (overlap(a, tile[t])) emit_pair(out, i, j0 + t);
  }
}

// The axis of largest variance (the lowest on ties), the same in every thread.
__host__ __device__ inline int sweep_axis(const FrameState& frame, unsigned n) {
  int best = 0;
  double best_variance = -1;
  for (int a = 0; a < 3; ++a) {
    const double mean = frame.sum[a] / double(n);
    const double variance = frame.square[a] / double(n) - mean * mean;
    if (variance > best_variance) {
      best = a;
      best_variance = variance;
    }
  }
  return best;
}

__device__ __forceinline__ float axis_value(float4 s, int axis) {
  return axis == 0 ? s.x : (axis == 1 ? s.y : s.z);
}

// Sort-and-sweep, 1: each sphere's key, the ordered bits of its interval's low end along
// the sweep axis; its index as the value.
__global__ void sweep_keys_kernel(const float4* spheres, unsigned n, const FrameState* frame,
                                  unsigned* keys, unsigned* ids) {
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float4 s = spheres[i];
  keys[i] = ordered_bits(geometry::cull_low(axis_value(s, sweep_axis(*frame, n)), s.w));
  ids[i] = i;
}

// Sort-and-sweep, 2: the spheres in sorted order with their intervals.
__global__ void sweep_gather_kernel(const float4* spheres, const unsigned* sorted_keys,
                                    const unsigned* sorted_ids, unsigned n, const FrameState* frame,
                                    float4* sorted, float* low, float* high) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const float4 s = spheres[sorted_ids[k]];
  sorted[k] = s;
  low[k] = from_ordered_bits(sorted_keys[k]);
  high[k] = geometry::cull_high(axis_value(s, sweep_axis(*frame, n)), s.w);
}

// Sort-and-sweep, 3: sphere k against every later one whose interval starts before its
// own ends.
__global__ void sweep_kernel(const float4* sorted, const float* low, const float* high,
                             const unsigned* sorted_ids, unsigned n, PairOutput out) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const float4 a = sorted[k];
  const float end = high[k];
  const unsigned id = sorted_ids[k];
  for (unsigned m = k + 1; m < n && low[m] <= end; ++m) {
    if (overlap(a, sorted[m])) emit_pair(out, id, sorted_ids[m]);
  }
}

// The uniform grid of the frame's centres and radii, the same in every thread (and on the
// host, from the frame read back).
__host__ __device__ inline grid::GridFrame grid_frame(const FrameState& frame) {
  float low[3], high[3];
  for (int a = 0; a < 3; ++a) {
    low[a] = from_ordered_bits(frame.low[a]);
    high[a] = from_ordered_bits(frame.high[a]);
  }
  return grid::make_grid_frame(low, high, from_ordered_bits(frame.radius_max));
}

// Grid, 1: each sphere's cell key; its index as the value.
__global__ void grid_keys_kernel(const float4* spheres, unsigned n, const FrameState* frame,
                                 unsigned long long* keys, unsigned* ids) {
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const float4 s = spheres[i];
  keys[i] = grid::cell_key_of(s.x, s.y, s.z, grid_frame(*frame));
  ids[i] = i;
}

// Grid, 2: the spheres in cell order.
__global__ void grid_gather_kernel(const float4* spheres, const unsigned* sorted_ids, unsigned n,
                                   float4* sorted) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  sorted[k] = spheres[sorted_ids[k]];
}

// Grid, 3: sphere k (sorted position) against the later spheres of its neighbouring cells.
__global__ void grid_pairs_kernel(const float4* sorted, const unsigned long long* sorted_keys,
                                  const unsigned* sorted_ids, unsigned n, PairOutput out) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const unsigned id = sorted_ids[k];
  grid::query_later(reinterpret_cast<const float*>(sorted), sorted_keys, n, k,
                    [&](unsigned m) { emit_pair(out, id, sorted_ids[m]); });
}

// LBVH, 1: each sphere's Morton code within the centres' bounds; its index as the value.
__global__ void lbvh_codes_kernel(const float4* spheres, unsigned n, const FrameState* frame,
                                  std::uint32_t* codes, unsigned* ids) {
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  float lo[3], size[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = from_ordered_bits(frame->low[a]);
    size[a] = from_ordered_bits(frame->high[a]) - lo[a];
  }
  const float4 s = spheres[i];
  const float c[3] = {s.x, s.y, s.z};
  codes[i] = lbvh::morton_code(c, lo, size);
  ids[i] = i;
}

// LBVH, 2: the spheres in Morton order and their boxes (the leaves).
__global__ void lbvh_leaves_kernel(const float4* spheres, const unsigned* sorted_ids, unsigned n,
                                   float4* sorted, lbvh::Box* leaf_boxes) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const float4 s = spheres[sorted_ids[k]];
  sorted[k] = s;
  leaf_boxes[k] = lbvh::sphere_box(s.x, s.y, s.z, s.w);
}

// LBVH, 3: internal node i of the radix tree, its children's parent links (internal
// nodes at 0 .. n-2, leaves at n-1 .. 2n-2; the root's parent -1), its refit flag cleared.
__global__ void lbvh_nodes_kernel(const std::uint32_t* sorted_codes, unsigned n, lbvh::Node* nodes,
                                  int* parents, unsigned* flags) {
  const unsigned i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i + 1 >= n) return;
  const lbvh::Node node = lbvh::radix_node(sorted_codes, int(n), int(i));
  nodes[i] = node;
  parents[node.left >= 0 ? node.left : int(n) - 1 + ~node.left] = int(i);
  parents[node.right >= 0 ? node.right : int(n) - 1 + ~node.right] = int(i);
  flags[i] = 0;
  if (i == 0) parents[0] = -1;
}

// A box another thread of this kernel wrote: read past the L1 cache.
__device__ __forceinline__ lbvh::Box load_box(const lbvh::Box* box) {
  lbvh::Box b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = __ldcg(&box->lo[k]);
    b.hi[k] = __ldcg(&box->hi[k]);
  }
  return b;
}

// LBVH, 4: the internal nodes' boxes, bottom-up: a thread per leaf climbs; at each node
// the first of the two children to arrive stops, the second merges both boxes.
__global__ void lbvh_refit_kernel(const lbvh::Node* nodes, const int* parents,
                                  const lbvh::Box* leaf_boxes, lbvh::Box* node_boxes,
                                  unsigned* flags, unsigned n) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  int node = parents[n - 1 + k];
  while (node >= 0) {
    __threadfence();  // this thread's box written before its arrival is counted
    if (atomicAdd(&flags[node], 1u) == 0) return;
    const lbvh::Node x = nodes[node];
    const lbvh::Box a = x.left < 0 ? leaf_boxes[~x.left] : load_box(&node_boxes[x.left]);
    const lbvh::Box b = x.right < 0 ? leaf_boxes[~x.right] : load_box(&node_boxes[x.right]);
    node_boxes[node] = lbvh::merge(a, b);
    node = parents[node];
  }
}

// LBVH, 5: sphere k (sorted position) queries the tree for its later overlapping spheres.
__global__ void lbvh_pairs_kernel(const lbvh::Node* nodes, const lbvh::Box* node_boxes,
                                  const lbvh::Box* leaf_boxes, const float4* sorted,
                                  const unsigned* sorted_ids, unsigned n, PairOutput out) {
  const unsigned k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const unsigned id = sorted_ids[k];
  lbvh::query_later(nodes, node_boxes, leaf_boxes, reinterpret_cast<const float*>(sorted), int(k),
                    [&](int m) { emit_pair(out, id, sorted_ids[m]); });
}

}  // namespace gplanner::detail::broad_phase
