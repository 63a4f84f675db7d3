// The GPU k-NN search: argument checks, device buffers kept between calls, and the
// launch sequence (extents -> Morton keys -> radix sort -> sorted tiles and their boxes
// -> search). Kernels are in gpu_nearest_neighbors_device.cuh.

#include <cuda_runtime.h>

#include <algorithm>
#include <cub/device/device_radix_sort.cuh>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

#include "gplanner/common/cuda_memory.cuh"
#include "gplanner/common/gpu_device.h"
#include "gplanner/knn_gpu/nearest_neighbors.h"
#include "gpu_nearest_neighbors_device.cuh"
#include "knn_checks.h"

namespace gplanner {
namespace {

void check_cuda(cudaError_t status, const char* what) {
  cuda::check(status, "GPU k-NN: CUDA", what);
}

using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

using cuda::blocks_for;

constexpr int kSearchBlock = 128;  // threads per search block: 4 warps, 4 query tiles
// Fewer query tiles than this (at most 32,768 points) are searched in slices (up to
// detail::kMaxSlices), so that about this many warps run.
constexpr int kBusyWarps = 1024;
constexpr std::size_t kSharedLimitBytes = 48 * 1024;

}  // namespace

bool gpu_nearest_neighbors_available(std::string* reason) {
  const GpuDevice device = query_gpu_device();
  if (!device.available && reason) *reason = device.reason;
  return device.available;
}

struct GpuNearestNeighbors::Impl {
  int device = 0;
  std::string device_name;
  GpuKnnStats stats;
  // Owned, made once a device is known to be there; the handles below are theirs.
  std::optional<cuda::Stream> owned_stream;
  std::optional<cuda::Event> owned_events[4];
  cudaStream_t stream = nullptr;
  cudaEvent_t start = nullptr, search_start = nullptr, search_stop = nullptr, stop = nullptr;

  DeviceBuffer<float> points;      // shape [n, width], input order
  DeviceBuffer<unsigned> extents;  // shape [2, embedding width]: lo, hi (ordered bits)
  DeviceBuffer<detail::MortonAxes> axes;
  DeviceBuffer<std::uint64_t> keys, sorted_keys;  // shape [n]
  DeviceBuffer<int> order, sorted_order;          // shape [n]
  DeviceBuffer<unsigned char> sort_scratch;
  DeviceBuffer<float> sorted_points;            // shape [tiles * 32, width]
  DeviceBuffer<int> ids;                        // shape [tiles * 32]
  DeviceBuffer<float> boxes;                    // shape [tiles, 2, width]
  DeviceBuffer<int> indices;                    // shape [n, k]
  DeviceBuffer<float> distances;                // shape [n, k]
  DeviceBuffer<int> part_indices;               // shape [slices, tiles * 32, k]
  DeviceBuffer<float> part_distances;           // shape [slices, tiles * 32, k]
  DeviceBuffer<unsigned long long> counters;    // shape [3]
  PinnedBuffer<int> h_indices;                  // shape [n, k]
  PinnedBuffer<float> h_distances;              // shape [n, k]
  PinnedBuffer<unsigned long long> h_counters;  // shape [3]

  // Made with `index` the current device (GpuDeviceScope).
  Impl(int index, const std::string& name) : device(index), device_name(name) {
    stream = owned_stream.emplace().get();
    int e = 0;
    for (cudaEvent_t* event : {&start, &search_start, &search_stop, &stop})
      *event = owned_events[e++].emplace().get();
    counters.reserve(3);
    h_counters.reserve(3);
    axes.reserve(1);
  }

  template <int K>
  void launch_search(const detail::KnnView& view, int k, float radius, int warps_per_block,
                     std::size_t shared_bytes, int slices) {
    const dim3 blocks(blocks_for(view.tiles, warps_per_block), slices);
    const int threads = warps_per_block * detail::kTile;
    int* out_i = slices > 1 ? part_indices.get() : indices.get();
    float* out_d = slices > 1 ? part_distances.get() : distances.get();
    if (view.metric.base == MetricBase::kFloating) {
      detail::all_knn_kernel<K, true><<<blocks, threads, shared_bytes, stream>>>(
          view, k, radius, out_i, out_d, counters.get());
    } else {
      detail::all_knn_kernel<K, false><<<blocks, threads, shared_bytes, stream>>>(
          view, k, radius, out_i, out_d, counters.get());
    }
  }

  // Checks the arguments, then enqueues the search of `count` points on the stream (the
  // upload to the merged indices and distances on the device); the caller then enqueues
  // its downloads and calls finish(). Returns false for no points (nothing enqueued).
  bool enqueue_search(const ConfigurationMetric& metric, const float* h_points, std::size_t count,
                      int k, float radius) {
    detail::check_knn_arguments(metric, count, k, radius);
    if (k > kMaxGpuNeighbors) {
      throw std::invalid_argument("GPU k-NN: k = " + std::to_string(k) + " exceeds the limit " +
                                  std::to_string(kMaxGpuNeighbors) +
                                  " (kMaxGpuNeighbors); ask for fewer neighbours or use "
                                  "all_nearest_neighbors_cpu()");
    }
    const int width = metric.width();
    const int stride = width | 1;
    const std::size_t warp_bytes = detail::knn_shared_floats_per_warp(stride) * sizeof(float);
    if (warp_bytes > kSharedLimitBytes) {
      throw std::invalid_argument(
          "GPU k-NN: configurations of " + std::to_string(width) +
          " floats exceed the search's shared-memory limit (at most " +
          std::to_string((kSharedLimitBytes / sizeof(float) - detail::kTile) / (2 * detail::kTile) -
                         1) +
          " floats); use all_nearest_neighbors_cpu()");
    }
    stats = {};
    if (count == 0) return false;

    const int n = static_cast<int>(count);
    const int tiles = (n + detail::kTile - 1) / detail::kTile;
    const int rows = tiles * detail::kTile;
    const int embedding_dims = detail::embedding_width(metric);
    points.reserve(count * width);
    extents.reserve(2 * std::max(embedding_dims, 1));
    keys.reserve(count);
    sorted_keys.reserve(count);
    order.reserve(count);
    sorted_order.reserve(count);
    sorted_points.reserve(static_cast<std::size_t>(rows) * width);
    ids.reserve(rows);
    boxes.reserve(static_cast<std::size_t>(tiles) * 2 * width);
    indices.reserve(count * k);
    distances.reserve(count * k);
    const int slices = std::clamp(kBusyWarps / tiles, 1, detail::kMaxSlices);
    if (slices > 1) {
      part_indices.reserve(static_cast<std::size_t>(slices) * rows * k);
      part_distances.reserve(static_cast<std::size_t>(slices) * rows * k);
    }
    std::size_t sort_bytes = 0;
    check_cuda(cub::DeviceRadixSort::SortPairs(nullptr, sort_bytes, keys.get(), sorted_keys.get(),
                                               order.get(), sorted_order.get(), n, 0, 63, stream),
               "radix sort size");
    sort_scratch.reserve(sort_bytes);

    check_cuda(cudaEventRecord(start, stream), "event");
    if (width > 0) {
      check_cuda(cudaMemcpyAsync(points.get(), h_points, count * width * sizeof(float),
                                 cudaMemcpyHostToDevice, stream),
                 "upload points");
    }
    check_cuda(cudaMemsetAsync(counters.get(), 0, 3 * sizeof(unsigned long long), stream),
               "memset");

    // Order the points along a Morton curve through their widest embedding coordinates.
    unsigned* d_lo = extents.get();
    unsigned* d_hi = d_lo + embedding_dims;
    if (embedding_dims > 0) {
      check_cuda(cudaMemsetAsync(d_lo, 0xff, embedding_dims * sizeof(unsigned), stream), "memset");
      check_cuda(cudaMemsetAsync(d_hi, 0, embedding_dims * sizeof(unsigned), stream), "memset");
      const int blocks = std::min(blocks_for(count, 256), 64);
      detail::embedding_extents_kernel<<<dim3(blocks, embedding_dims), 256, 0, stream>>>(
          metric, points.get(), n, d_lo, d_hi);
    }
    detail::morton_axes_kernel<<<1, 1, 0, stream>>>(embedding_dims, d_lo, d_hi, axes.get());
    detail::morton_key_kernel<<<blocks_for(count, 256), 256, 0, stream>>>(metric, points.get(), n,
                                                                          axes.get(), keys.get());
    detail::iota_kernel<<<blocks_for(count, 256), 256, 0, stream>>>(order.get(), n);
    check_cuda(cudaGetLastError(), "key kernels");
    check_cuda(cub::DeviceRadixSort::SortPairs(sort_scratch.get(), sort_bytes, keys.get(),
                                               sorted_keys.get(), order.get(), sorted_order.get(),
                                               n, 0, 63, stream),
               "radix sort");

    // Tiles of 32 consecutive points and their boxes.
    detail::gather_kernel<<<blocks_for(rows, 256), 256, 0, stream>>>(
        points.get(), n, width, sorted_order.get(), rows, sorted_points.get(), ids.get());
    const detail::KnnView view{metric,    width,      stride, tiles, sorted_points.get(),
                               ids.get(), boxes.get()};
    detail::tile_boxes_kernel<<<blocks_for(rows, 128), 128, 0, stream>>>(view, boxes.get());
    check_cuda(cudaGetLastError(), "tile kernels");

    const int warps_per_block = static_cast<int>(
        std::min<std::size_t>(kSearchBlock / detail::kTile, kSharedLimitBytes / warp_bytes));
    const std::size_t shared_bytes = warps_per_block * warp_bytes;
    check_cuda(cudaEventRecord(search_start, stream), "event");
    if (k <= 16) {
      launch_search<16>(view, k, radius, warps_per_block, shared_bytes, slices);
    } else if (k <= 32) {
      launch_search<32>(view, k, radius, warps_per_block, shared_bytes, slices);
    } else {
      launch_search<kMaxGpuNeighbors>(view, k, radius, warps_per_block, shared_bytes, slices);
    }
    check_cuda(cudaGetLastError(), "search kernel");
    if (slices > 1) {
      detail::merge_slices_kernel<<<blocks_for(count, 128), 128, 0, stream>>>(
          n, rows, k, slices, part_indices.get(), part_distances.get(), indices.get(),
          distances.get());
      check_cuda(cudaGetLastError(), "merge kernel");
    }
    check_cuda(cudaEventRecord(search_stop, stream), "event");
    stats.tiles = tiles;
    stats.slices = slices;
    return true;
  }

  // Downloads the counters after the caller's downloads, waits for the stream, and
  // records the call's times and counts in `stats`.
  void finish() {
    check_cuda(cudaMemcpyAsync(h_counters.get(), counters.get(), 3 * sizeof(unsigned long long),
                               cudaMemcpyDeviceToHost, stream),
               "download counters");
    check_cuda(cudaEventRecord(stop, stream), "event");
    check_cuda(cudaEventSynchronize(stop), "search");

    float total_ms = 0, search_ms = 0;
    check_cuda(cudaEventElapsedTime(&total_ms, start, stop), "event");
    check_cuda(cudaEventElapsedTime(&search_ms, search_start, search_stop), "event");
    stats.milliseconds = total_ms;
    stats.search_milliseconds = search_ms;
    stats.tiles_visited = h_counters.get()[0];
    stats.candidate_pairs = h_counters.get()[1];
    stats.distance_evaluations = h_counters.get()[2];
  }

  NeighborTable all_nearest(const ConfigurationMetric& metric, const float* h_points,
                            std::size_t count, int k, float radius) {
    NeighborTable table;
    table.k = k;
    table.rows = count;
    if (!enqueue_search(metric, h_points, count, k, radius)) return table;
    h_indices.reserve(count * k);
    h_distances.reserve(count * k);
    check_cuda(cudaMemcpyAsync(h_indices.get(), indices.get(), count * k * sizeof(int),
                               cudaMemcpyDeviceToHost, stream),
               "download indices");
    check_cuda(cudaMemcpyAsync(h_distances.get(), distances.get(), count * k * sizeof(float),
                               cudaMemcpyDeviceToHost, stream),
               "download distances");
    finish();
    table.indices.assign(h_indices.get(), h_indices.get() + count * k);
    table.distances.assign(h_distances.get(), h_distances.get() + count * k);
    return table;
  }

  void nearest_rows(const ConfigurationMetric& metric, const float* h_points, std::size_t count,
                    int k, std::size_t first, std::size_t end, int* h_rows, float radius) {
    if (first > end || end > count) {
      throw std::invalid_argument("GPU k-NN: rows [" + std::to_string(first) + ", " +
                                  std::to_string(end) + ") are not among the " +
                                  std::to_string(count) + " points");
    }
    if (!enqueue_search(metric, h_points, count, k, radius)) return;  // no points
    // Into the caller's memory directly (pageable: the driver stages it): no pinned
    // buffer to grow as the roadmap does, and no copy after.
    if (first < end) {
      check_cuda(cudaMemcpyAsync(h_rows, indices.get() + first * k, (end - first) * k * sizeof(int),
                                 cudaMemcpyDeviceToHost, stream),
                 "download indices");
    }
    finish();
  }
};

GpuNearestNeighbors::GpuNearestNeighbors(int device) {
  const GpuDevice gpu = query_gpu_device(device);
  if (!gpu.available) {
    throw std::runtime_error("GPU k-NN: no usable GPU (" + gpu.reason +
                             "); use all_nearest_neighbors_cpu()");
  }
  const GpuDeviceScope scope(device);
  impl_ = std::make_unique<Impl>(device, gpu.name);
}

GpuNearestNeighbors::~GpuNearestNeighbors() {
  // Its buffers freed on its device; where that cannot be made current (the runtime
  // unloading at the process's exit), as they can be: a destructor throws nothing.
  std::optional<GpuDeviceScope> scope;
  try {
    scope.emplace(impl_->device);
  } catch (const std::exception&) {
  }
  impl_.reset();
}

NeighborTable GpuNearestNeighbors::all_nearest(const ConfigurationMetric& metric,
                                               const float* points, std::size_t n, int k,
                                               float radius) {
  const GpuDeviceScope scope(impl_->device);
  return impl_->all_nearest(metric, points, n, k, radius);
}

void GpuNearestNeighbors::nearest_rows(const ConfigurationMetric& metric, const float* points,
                                       std::size_t n, int k, std::size_t first, std::size_t end,
                                       int* indices, float radius) {
  const GpuDeviceScope scope(impl_->device);
  impl_->nearest_rows(metric, points, n, k, first, end, indices, radius);
}

const GpuKnnStats& GpuNearestNeighbors::last_stats() const { return impl_->stats; }

std::string GpuNearestNeighbors::device_name() const { return impl_->device_name; }

}  // namespace gplanner
