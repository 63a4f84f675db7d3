#pragma once
// Device code of the GPU k-NN search: Morton keys of the points, tile boxes, and the
// search kernel (one warp per tile of 32 query points). The metric and its bounds come
// from configuration_metric.h and detail/metric_bounds.h, shared with the CPU.

#include <climits>
#include <cstddef>
#include <cstdint>

#include "gplanner/knn_gpu/configuration_metric.h"
#include "gplanner/knn_gpu/detail/metric_bounds.h"

namespace gplanner {
namespace detail {

constexpr int kTile = 32;  // points per tile: one per lane of a warp
constexpr unsigned kFullMask = 0xffffffffu;
constexpr int kNoNeighbor = INT_MAX;  // index of an empty slot while searching

// What the search kernel reads, passed by value; the buffers belong to the host class.
struct KnnView {
  ConfigurationMetric metric;
  int width;   // floats per configuration
  int stride;  // floats per row in shared memory: width made odd, free of bank conflicts
  int tiles;
  const float* d_points;  // shape [tiles * kTile, width]: sorted along the Morton curve
  const int* d_ids;       // shape [tiles * kTile]: each row's input index, -1 for padding
  const float* d_boxes;   // shape [tiles, 2, width]: lo row then hi row, box coordinates
};

// The Morton curve's axes: chosen embedding coordinates, their origin and a common cell.
struct MortonAxes {
  int count;                 // axes used, <= kMaxMortonAxes (0: all points alike)
  int bits;                  // bits per axis
  int dims[kMaxMortonAxes];  // embedding coordinate of each axis
  float lo[kMaxMortonAxes];  // its smallest value
  float cells_per_unit;      // cells per unit of embedding coordinate, the same on every axis
};

// Floats as unsigned integers of the same order, for atomicMin / atomicMax.
__device__ inline unsigned ordered_bits(float f) {
  const unsigned u = __float_as_uint(f);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
__device__ inline float from_ordered_bits(unsigned u) {
  return __uint_as_float((u & 0x80000000u) ? (u & 0x7fffffffu) : ~u);
}

__global__ void iota_kernel(int* d_ids, int n) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) d_ids[i] = i;
}

// Extents of every embedding coordinate; blockIdx.y is the coordinate.
// d_points: shape [n, width]; d_lo, d_hi: shape [embedding_width], ordered_bits().
__global__ void embedding_extents_kernel(ConfigurationMetric m, const float* d_points, int n,
                                         unsigned* d_lo, unsigned* d_hi) {
  const int e = blockIdx.y, width = m.width();
  float lo = INFINITY, hi = -INFINITY;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
    const float x = embedding_coordinate(m, d_points + static_cast<std::size_t>(i) * width, e);
    lo = fminf(lo, x);
    hi = fmaxf(hi, x);
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    lo = fminf(lo, __shfl_xor_sync(kFullMask, lo, offset));
    hi = fmaxf(hi, __shfl_xor_sync(kFullMask, hi, offset));
  }
  if ((threadIdx.x & 31) == 0) {
    atomicMin(d_lo + e, ordered_bits(lo));
    atomicMax(d_hi + e, ordered_bits(hi));
  }
}

// Picks the (up to) kMaxMortonAxes embedding coordinates of widest finite spread; run by
// one thread. d_lo, d_hi: shape [embedding_dims], ordered_bits().
__global__ void morton_axes_kernel(int embedding_dims, const unsigned* d_lo, const unsigned* d_hi,
                                   MortonAxes* d_axes) {
  MortonAxes axes{};
  float widest = 0;
  for (int a = 0; a < kMaxMortonAxes; ++a) {
    int best = -1;
    float best_range = 0;
    for (int e = 0; e < embedding_dims; ++e) {
      bool used = false;
      for (int b = 0; b < axes.count; ++b) used = used || axes.dims[b] == e;
      const float range = from_ordered_bits(d_hi[e]) - from_ordered_bits(d_lo[e]);
      if (!used && range > best_range && range < INFINITY) {  // NaN fails both
        best = e;
        best_range = range;
      }
    }
    if (best < 0) break;
    axes.dims[axes.count] = best;
    axes.lo[axes.count] = from_ordered_bits(d_lo[best]);
    ++axes.count;
    widest = fmaxf(widest, best_range);
  }
  axes.bits = axes.count > 0 ? min(21, 63 / axes.count) : 0;
  axes.cells_per_unit = axes.count > 0 ? static_cast<float>(1u << axes.bits) / widest : 0;
  *d_axes = axes;
}

// d_points: shape [n, width]; d_keys: shape [n].
__global__ void morton_key_kernel(ConfigurationMetric m, const float* d_points, int n,
                                  const MortonAxes* d_axes, std::uint64_t* d_keys) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const MortonAxes axes = *d_axes;
  const float* q = d_points + static_cast<std::size_t>(i) * m.width();
  const float top = static_cast<float>((1u << axes.bits) - 1);
  std::uint32_t cells[kMaxMortonAxes];
  for (int a = 0; a < axes.count; ++a) {
    const float x = (embedding_coordinate(m, q, axes.dims[a]) - axes.lo[a]) * axes.cells_per_unit;
    cells[a] = static_cast<std::uint32_t>(fminf(fmaxf(x, 0.0f), top));
  }
  d_keys[i] = morton_code(cells, axes.count, axes.bits);
}

// Sorted, padded copy of the points; one thread per row. d_points: shape [n, width];
// d_order: shape [n], the input index of each sorted row; d_sorted: shape [rows, width];
// d_ids: shape [rows].
__global__ void gather_kernel(const float* d_points, int n, int width, const int* d_order, int rows,
                              float* d_sorted, int* d_ids) {
  const int r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r >= rows) return;
  const int id = r < n ? d_order[r] : -1;
  float* out = d_sorted + static_cast<std::size_t>(r) * width;
  if (id >= 0) {
    const float* in = d_points + static_cast<std::size_t>(id) * width;
    for (int c = 0; c < width; ++c) out[c] = in[c];
  } else {
    for (int c = 0; c < width; ++c) out[c] = 0.0f;
  }
  d_ids[r] = id;
}

// One warp per tile: the box of its points in box coordinates. d_boxes: shape
// [tiles, 2, width].
__global__ void tile_boxes_kernel(KnnView v, float* d_boxes) {
  const int tile = (blockIdx.x * blockDim.x + threadIdx.x) / kTile, lane = threadIdx.x % kTile;
  if (tile >= v.tiles) return;
  const int row = tile * kTile + lane;
  const bool valid = v.d_ids[row] >= 0;
  const float* q = v.d_points + static_cast<std::size_t>(row) * v.width;
  float* lo = d_boxes + static_cast<std::size_t>(tile) * 2 * v.width;
  for (int c = 0; c < v.width; ++c) {
    const float x = valid ? box_coordinate(v.metric, q, c) : 0.0f;
    float low = valid ? x : INFINITY, high = valid ? x : -INFINITY;
    for (int offset = 16; offset > 0; offset /= 2) {
      low = fminf(low, __shfl_xor_sync(kFullMask, low, offset));
      high = fmaxf(high, __shfl_xor_sync(kFullMask, high, offset));
    }
    if (lane == 0) {
      lo[c] = low;
      lo[v.width + c] = high;
    }
  }
}

// The s-th tile outward from tile `home` along the curve: home, +1, -1, +2, -2, ...
__device__ inline int tile_outward(int home, int s) {
  const int step = (s + 1) / 2;
  return (s & 1) ? home + step : home - step;
}

// Inserts (d, id) into a lane's sorted list of its k best (slots [0, k) of K, in
// registers: every index is a compile-time constant once unrolled) and updates the k-th.
template <int K>
__device__ inline void insert_neighbor(float (&best_d)[K], int (&best_i)[K], int k, float d, int id,
                                       float* worst_d, int* worst_i) {
#pragma unroll
  for (int r = 0; r < K; ++r) {
    if (r < k) {
      if (neighbor_before(d, id, best_d[r], best_i[r])) {
        const float carried_d = best_d[r];
        const int carried_i = best_i[r];
        best_d[r] = d;
        best_i[r] = id;
        d = carried_d;
        id = carried_i;
      }
      if (r == k - 1) {
        *worst_d = best_d[r];
        *worst_i = best_i[r];
      }
    }
  }
}

// Shared memory per warp: query rows, candidate rows (each [kTile, stride]) and
// candidate ids [kTile].
__host__ __device__ inline int knn_shared_floats_per_warp(int stride) {
  return 2 * kTile * stride + kTile;
}

// Copies tile `tile` of the sorted points (rows of `width` floats) into shared memory
// rows of `stride` floats, the whole warp together.
__device__ inline void stage_tile(const KnnView& v, int tile, int lane, float* rows) {
  const float* source = v.d_points + static_cast<std::size_t>(tile) * kTile * v.width;
  if (v.stride == v.width) {
    for (int e = lane; e < kTile * v.width; e += kTile) rows[e] = source[e];
  } else {
    for (int e = lane; e < kTile * v.width; e += kTile)
      rows[(e / v.width) * v.stride + e % v.width] = source[e];
  }
}

// One warp per query tile; lane = query point. Candidate tiles are visited outward along
// the curve, 32 at a time: first a box-to-box bound against the warp's widest cut-off
// drops most of them, then each surviving tile is loaded into shared memory only if some
// lane's own point-to-box bound does not exceed that lane's cut-off (its k-th distance
// or the radius). In a loaded tile, a floating base first sifts the candidates with
// floating_base_lower_bound(), lanes taking candidates and the warp walking the lanes
// that want the tile (one ballot each), and only those that pass get the exact
// distance; other metrics evaluate every candidate exactly.
// With several slices (gridDim.y; few tiles, so that one warp per tile would leave the
// GPU idle), slice y visits only the outward steps s with s % slices == y and writes its
// own k best, unmerged (merge_slices_kernel merges them).
// d_indices, d_distances: shape [n, k] in input order, or [slices, tiles * 32, k] with
// several slices (empty slots: kNoNeighbor); d_counters: shape [3] (tiles loaded,
// candidate pairs, exact distance evaluations). At k <= 16, six blocks of four
// warps per SM (85 registers a thread) keep 100,000 points' 3,125 warps resident on 132
// SMs at once.
template <int K, bool kFloatingBase>
__global__ void __launch_bounds__(128, K <= 16 ? 6 : 2)
    all_knn_kernel(KnnView v, int k, float radius, int* d_indices, float* d_distances,
                   unsigned long long* d_counters) {
  extern __shared__ float shared[];
  const int warp = threadIdx.x / kTile, lane = threadIdx.x % kTile;
  const int tile = blockIdx.x * (blockDim.x / kTile) + warp;
  if (tile >= v.tiles) return;  // whole warps only
  const int slices = gridDim.y, slice = blockIdx.y;
  const ConfigurationMetric& m = v.metric;
  const int width = v.width, stride = v.stride;
  float* query_rows = shared + warp * knn_shared_floats_per_warp(stride);
  float* candidate_rows = query_rows + kTile * stride;
  int* candidate_ids = reinterpret_cast<int*>(candidate_rows + kTile * stride);

  stage_tile(v, tile, lane, query_rows);
  const int my_id = v.d_ids[tile * kTile + lane];
  __syncwarp();
  const float* q = query_rows + lane * stride;
  float best_d[K];
  int best_i[K];
#pragma unroll
  for (int r = 0; r < K; ++r) {
    best_d[r] = INFINITY;
    best_i[r] = kNoNeighbor;
  }
  float worst_d = INFINITY;
  int worst_i = kNoNeighbor;
  // A padding lane wants nothing: its cut-off is below every bound.
  auto cutoff = [&]() { return my_id < 0 ? -1.0f : fminf(worst_d, radius); };

  const float* home_lo = v.d_boxes + static_cast<std::size_t>(tile) * 2 * width;
  const float* home_hi = home_lo + width;
  unsigned long long loaded = 0, pairs = 0, evaluations = 0;
  for (int first = 0; first < 2 * v.tiles; first += kTile) {
    float warp_cutoff = cutoff();
    for (int offset = 16; offset > 0; offset /= 2)
      warp_cutoff = fmaxf(warp_cutoff, __shfl_xor_sync(kFullMask, warp_cutoff, offset));
    const int s = first + lane;
    const int t = tile_outward(tile, s);
    bool candidate = false;
    if (s < 2 * v.tiles && s % slices == slice && t >= 0 && t < v.tiles) {
      const float* lo = v.d_boxes + static_cast<std::size_t>(t) * 2 * width;
      candidate = !prunable(box_box_lower_bound(m, home_lo, home_hi, lo, lo + width), warp_cutoff);
    }
    unsigned pending = __ballot_sync(kFullMask, candidate);
    while (pending) {
      const int bit = __ffs(pending) - 1;
      pending &= pending - 1;
      const int ct = tile_outward(tile, first + bit);
      const float* lo = v.d_boxes + static_cast<std::size_t>(ct) * 2 * width;
      const bool wanted =
          my_id >= 0 && !prunable(point_box_lower_bound(m, q, lo, lo + width), cutoff());
      if (!__any_sync(kFullMask, wanted)) continue;
      __syncwarp();  // every lane is done with the previous candidate tile
      stage_tile(v, ct, lane, candidate_rows);
      const int candidate_id = v.d_ids[ct * kTile + lane];
      candidate_ids[lane] = candidate_id;
      // Bit j: candidate j is a real point, not the lane's own (row `lane` of its own tile).
      const unsigned others =
          __ballot_sync(kFullMask, candidate_id >= 0) & ~(ct == tile ? 1u << lane : 0u);
      __syncwarp();
      ++loaded;
      unsigned maybe = kFullMask;  // bit j: candidate j may beat the lane's cut-off
      if (kFloatingBase) {
        // Lane = candidate here: its pose in registers, the wanting queries' poses read
        // by all lanes at once, two queries a step.
        float c_base[7];
        for (int c = 0; c < 7; ++c) c_base[c] = candidate_rows[lane * stride + c];
        const float limit = prune_limit(cutoff());
        unsigned wanting = __ballot_sync(kFullMask, wanted);
        while (wanting) {
          const int qa = __ffs(wanting) - 1;
          wanting &= wanting - 1;
          const int qb = wanting ? __ffs(wanting) - 1 : qa;
          wanting &= wanting - 1;
          const float limit_a = __shfl_sync(kFullMask, limit, qa);
          const float limit_b = __shfl_sync(kFullMask, limit, qb);
          const float bound_a = floating_base_lower_bound(m, query_rows + qa * stride, c_base);
          const float bound_b = floating_base_lower_bound(m, query_rows + qb * stride, c_base);
          const unsigned pass_a = __ballot_sync(kFullMask, !(bound_a > limit_a));
          const unsigned pass_b = __ballot_sync(kFullMask, !(bound_b > limit_b));
          if (lane == qa) maybe = pass_a;
          if (lane == qb) maybe = pass_b;
        }
      }
      if (!wanted) continue;
      pairs += __popc(others);
      maybe &= others;
      while (maybe) {
        const int j = __ffs(maybe) - 1;
        maybe &= maybe - 1;
        const int id = candidate_ids[j];
        const float d = configuration_distance(m, q, candidate_rows + j * stride);
        ++evaluations;
        if (d <= radius && neighbor_before(d, id, worst_d, worst_i))
          insert_neighbor<K>(best_d, best_i, k, d, id, &worst_d, &worst_i);
      }
    }
  }

  if (my_id >= 0) {
    const std::size_t row = static_cast<std::size_t>(slice) * v.tiles * kTile + my_id;
    int* out_i = d_indices + row * k;
    float* out_d = d_distances + row * k;
#pragma unroll
    for (int r = 0; r < K; ++r) {
      if (r < k) {
        out_i[r] = best_i[r] == kNoNeighbor && slices == 1 ? -1 : best_i[r];
        out_d[r] = best_d[r];
      }
    }
  }
  for (int offset = 16; offset > 0; offset /= 2) {
    pairs += __shfl_xor_sync(kFullMask, pairs, offset);
    evaluations += __shfl_xor_sync(kFullMask, evaluations, offset);
  }
  if (lane == 0) {
    atomicAdd(d_counters, loaded);
    atomicAdd(d_counters + 1, pairs);
    atomicAdd(d_counters + 2, evaluations);
  }
}

constexpr int kMaxSlices = 16;

// Merges the slices' lists (each sorted by neighbor_before, each candidate in one slice
// only) into each point's k best: a thread per point. part_i, part_d: shape
// [slices, rows, k]; d_indices, d_distances: shape [n, k].
__global__ void merge_slices_kernel(int n, int rows, int k, int slices, const int* part_i,
                                    const float* part_d, int* d_indices, float* d_distances) {
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p >= n) return;
  int next[kMaxSlices];
  for (int s = 0; s < slices; ++s) next[s] = 0;
  for (int r = 0; r < k; ++r) {
    int best = -1;
    float best_d = INFINITY;
    int best_i = kNoNeighbor;
    for (int s = 0; s < slices; ++s) {
      if (next[s] >= k) continue;
      const std::size_t at = (static_cast<std::size_t>(s) * rows + p) * k + next[s];
      if (best < 0 || neighbor_before(part_d[at], part_i[at], best_d, best_i)) {
        best = s;
        best_d = part_d[at];
        best_i = part_i[at];
      }
    }
    ++next[best];
    d_indices[static_cast<std::size_t>(p) * k + r] = best_i == kNoNeighbor ? -1 : best_i;
    d_distances[static_cast<std::size_t>(p) * k + r] = best_d;
  }
}

}  // namespace detail
}  // namespace gplanner
