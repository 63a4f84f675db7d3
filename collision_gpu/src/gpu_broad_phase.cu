// The GPU sphere broad phase: buffers kept between frames, the launch sequence of each
// method, and the pair buffer that grows to the exact count when it overflows. Kernels are
// in gpu_broad_phase_device.cuh.

#include <cuda_runtime.h>

#include <algorithm>
#include <cstring>
#include <cub/device/device_radix_sort.cuh>
#include <stdexcept>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/gpu_broad_phase.h"
#include "gplanner/common/cuda_memory.cuh"
#include "gplanner/common/gpu_device.h"
#include "gpu_broad_phase_device.cuh"

namespace gplanner {
namespace {

namespace bp = detail::broad_phase;
using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

static_assert(sizeof(SpherePair) == sizeof(uint2), "pairs are copied as they lie");

void check_cuda(cudaError_t status, const char* what) {
  cuda::check(status, "GPU broad phase: CUDA", what);
}

unsigned blocks_for(std::size_t threads) {
  return static_cast<unsigned>((threads + bp::kBlock - 1) / bp::kBlock);
}

// The frame state before any sphere is seen.
bp::FrameState initial_frame() {
  bp::FrameState f{};
  for (int a = 0; a < 3; ++a) {
    f.low[a] = ~0u;
    f.high[a] = 0u;
  }
  f.radius_max = 0u;
  f.pairs = 0;
  f.bad = bp::kNoBadSphere;
  return f;
}

}  // namespace

bool gpu_broad_phase_available(std::string* reason) {
  const GpuDevice device = query_gpu_device();
  if (!device.available && reason) *reason = device.reason;
  return device.available;
}

struct GpuBroadPhase::Impl {
  std::string device_name;
  GpuBroadPhaseStats stats;
  cudaStream_t stream = nullptr;
  cudaEvent_t start = nullptr, stop = nullptr;

  PinnedBuffer<float> h_centers;         // shape [n, 3]: staging
  PinnedBuffer<float> h_radii;           // shape [n]
  PinnedBuffer<bp::FrameState> h_frame;  // shape [2]: the initial one, the one read back
  PinnedBuffer<uint2> h_pairs;           // shape [pair capacity]
  DeviceBuffer<float> d_centers;         // shape [n, 3]
  DeviceBuffer<float> d_radii;           // shape [n]
  DeviceBuffer<float4> d_spheres;        // shape [n]: x, y, z, r
  DeviceBuffer<float4> d_sorted;         // shape [n]: in sweep or cell order
  DeviceBuffer<unsigned> d_keys32, d_sorted_keys32;            // shape [n]
  DeviceBuffer<unsigned long long> d_keys64, d_sorted_keys64;  // shape [n]
  DeviceBuffer<unsigned> d_ids, d_sorted_ids;                  // shape [n]
  DeviceBuffer<float> d_low, d_high;                           // shape [n]
  DeviceBuffer<detail::lbvh::Node> d_nodes;                    // shape [n - 1]
  DeviceBuffer<detail::lbvh::Box> d_node_boxes;                // shape [n - 1]
  DeviceBuffer<detail::lbvh::Box> d_leaf_boxes;                // shape [n]
  DeviceBuffer<int> d_parents;                                 // shape [2n - 1]
  DeviceBuffer<unsigned> d_flags;                              // shape [n - 1]
  DeviceBuffer<unsigned char> d_sort_scratch;
  DeviceBuffer<bp::FrameState> d_frame;  // shape [1]
  DeviceBuffer<uint2> d_pairs;           // shape [pair capacity]
  std::size_t last_pairs = 0;            // the previous frame's count: what to download at once

  Impl() {
    const GpuDevice device = query_gpu_device();
    if (!device.available) {
      throw std::runtime_error("GPU broad phase: no usable GPU (" + device.reason +
                               "); use all_pairs_cpu() or sort_sweep_cpu()");
    }
    device_name = device.name;
    check_cuda(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), "stream");
    check_cuda(cudaEventCreate(&start), "event");
    check_cuda(cudaEventCreate(&stop), "event");
    h_frame.reserve(2);
    h_frame.get()[0] = initial_frame();
    d_frame.reserve(1);
    d_pairs.reserve(4096);
    h_pairs.reserve(4096);
  }

  ~Impl() {
    if (start) cudaEventDestroy(start);
    if (stop) cudaEventDestroy(stop);
    if (stream) cudaStreamDestroy(stream);
  }

  void launched(const char* what) {
    check_cuda(cudaGetLastError(), what);
    ++stats.kernels;
  }

  bp::PairOutput pair_output() const {
    return {d_pairs.get(), d_pairs.capacity(), &d_frame.get()->pairs};
  }

  template <typename Key>
  void sort(const Key* keys, Key* sorted_keys, unsigned n, int end_bit) {
    std::size_t bytes = 0;
    check_cuda(cub::DeviceRadixSort::SortPairs(nullptr, bytes, keys, sorted_keys, d_ids.get(),
                                               d_sorted_ids.get(), int(n), 0, end_bit, stream),
               "radix sort size");
    d_sort_scratch.reserve(bytes);
    check_cuda(
        cub::DeviceRadixSort::SortPairs(d_sort_scratch.get(), bytes, keys, sorted_keys, d_ids.get(),
                                        d_sorted_ids.get(), int(n), 0, end_bit, stream),
        "radix sort");
    ++stats.kernels;
  }

  // Everything before the pair kernel, then the pair kernel itself (run again on overflow).
  void prepare(BroadPhaseMethod method, unsigned n) {
    const unsigned blocks = blocks_for(n);
    if (method == BroadPhaseMethod::kGpuAllPairs) {
      bp::pack_kernel<false><<<blocks, bp::kBlock, 0, stream>>>(d_centers.get(), d_radii.get(), n,
                                                                d_spheres.get(), d_frame.get());
      launched("pack");
      return;
    }
    bp::pack_kernel<true><<<blocks, bp::kBlock, 0, stream>>>(d_centers.get(), d_radii.get(), n,
                                                             d_spheres.get(), d_frame.get());
    launched("pack");
    d_sorted.reserve(n);
    d_ids.reserve(n);
    d_sorted_ids.reserve(n);
    if (method == BroadPhaseMethod::kGpuSortSweep) {
      d_keys32.reserve(n);
      d_sorted_keys32.reserve(n);
      d_low.reserve(n);
      d_high.reserve(n);
      bp::sweep_keys_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame.get(),
                                                               d_keys32.get(), d_ids.get());
      launched("sweep keys");
      sort(d_keys32.get(), d_sorted_keys32.get(), n, 32);
      bp::sweep_gather_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_spheres.get(), d_sorted_keys32.get(), d_sorted_ids.get(), n, d_frame.get(),
          d_sorted.get(), d_low.get(), d_high.get());
      launched("sweep gather");
    } else if (method == BroadPhaseMethod::kGpuLbvh) {
      d_keys32.reserve(n);
      d_sorted_keys32.reserve(n);
      d_nodes.reserve(n - 1);
      d_node_boxes.reserve(n - 1);
      d_leaf_boxes.reserve(n);
      d_parents.reserve(2 * std::size_t(n) - 1);
      d_flags.reserve(n - 1);
      bp::lbvh_codes_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame.get(),
                                                               d_keys32.get(), d_ids.get());
      launched("lbvh codes");
      sort(d_keys32.get(), d_sorted_keys32.get(), n, 30);
      bp::lbvh_leaves_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_spheres.get(), d_sorted_ids.get(), n, d_sorted.get(), d_leaf_boxes.get());
      launched("lbvh leaves");
      bp::lbvh_nodes_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_sorted_keys32.get(), n, d_nodes.get(), d_parents.get(), d_flags.get());
      launched("lbvh nodes");
      bp::lbvh_refit_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_nodes.get(), d_parents.get(), d_leaf_boxes.get(), d_node_boxes.get(), d_flags.get(), n);
      launched("lbvh refit");
    } else {
      d_keys64.reserve(n);
      d_sorted_keys64.reserve(n);
      bp::grid_keys_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame.get(),
                                                              d_keys64.get(), d_ids.get());
      launched("grid keys");
      sort(d_keys64.get(), d_sorted_keys64.get(), n, 3 * bp::kCellBits);
      bp::grid_gather_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), d_sorted_ids.get(),
                                                                n, d_sorted.get());
      launched("grid gather");
    }
  }

  void find_pairs_kernel(BroadPhaseMethod method, unsigned n) {
    const unsigned blocks = blocks_for(n);
    if (method == BroadPhaseMethod::kGpuAllPairs) {
      bp::all_pairs_kernel<<<dim3(blocks, blocks), bp::kBlock, 0, stream>>>(d_spheres.get(), n,
                                                                            pair_output());
      launched("all pairs");
    } else if (method == BroadPhaseMethod::kGpuSortSweep) {
      bp::sweep_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_sorted.get(), d_low.get(), d_high.get(),
                                                          d_sorted_ids.get(), n, pair_output());
      launched("sweep");
    } else if (method == BroadPhaseMethod::kGpuLbvh) {
      bp::lbvh_pairs_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_nodes.get(), d_node_boxes.get(), d_leaf_boxes.get(), d_sorted.get(), d_sorted_ids.get(),
          n, pair_output());
      launched("lbvh pairs");
    } else {
      bp::grid_pairs_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_sorted.get(), d_sorted_keys64.get(), d_sorted_ids.get(), n, pair_output());
      launched("grid pairs");
    }
  }

  // Downloads the frame state and the first `count` pairs.
  void download(std::size_t count) {
    check_cuda(cudaMemcpyAsync(h_frame.get() + 1, d_frame.get(), sizeof(bp::FrameState),
                               cudaMemcpyDeviceToHost, stream),
               "download the frame");
    if (count > 0) {
      check_cuda(cudaMemcpyAsync(h_pairs.get(), d_pairs.get(), count * sizeof(uint2),
                                 cudaMemcpyDeviceToHost, stream),
                 "download the pairs");
    }
    check_cuda(cudaStreamSynchronize(stream), "the frame's kernels");
  }

  // The pair buffers grown to `count`, with a clear error where the device has no room.
  void grow_pairs(std::size_t count) {
    std::size_t free_bytes = 0, total_bytes = 0;
    check_cuda(cudaMemGetInfo(&free_bytes, &total_bytes), "free memory");
    const std::size_t bytes = count * sizeof(uint2);
    if (bytes > free_bytes + d_pairs.capacity() * sizeof(uint2)) {
      throw std::runtime_error("GPU broad phase: " + std::to_string(count) + " pairs (" +
                               std::to_string(bytes >> 20) + " MiB) do not fit the " +
                               std::to_string(free_bytes >> 20) +
                               " MiB free on the device; use fewer or smaller spheres");
    }
    d_pairs.reserve(count);
    h_pairs.reserve(count);
  }

  void find_pairs(BroadPhaseMethod method, const SphereArrays& s, std::vector<SpherePair>* pairs) {
    if (!is_gpu_method(method)) {
      throw std::invalid_argument(std::string("GPU broad phase: ") +
                                  broad_phase_method_name(method) +
                                  " is a CPU method; use all_pairs_cpu() or sort_sweep_cpu()");
    }
    if (s.n >= (std::size_t(1) << 31))
      throw std::invalid_argument("GPU broad phase: at most 2^31 - 1 spheres");
    if (s.n > 0 && (s.centers == nullptr || s.radii == nullptr))
      throw std::invalid_argument("GPU broad phase: null centre or radius array for n > 0");
    const unsigned n = static_cast<unsigned>(s.n);
    if (method == BroadPhaseMethod::kGpuAllPairs && blocks_for(n) > 65535) {
      throw std::invalid_argument("GPU broad phase: gpu-all-pairs takes at most " +
                                  std::to_string(65535 * bp::kBlock) +
                                  " spheres; use gpu-grid or gpu-sort-sweep");
    }
    stats = GpuBroadPhaseStats{};
    pairs->clear();
    if (n < 2) {
      check_spheres(s);  // nothing to launch: checked here
      return;
    }
    check_cuda(cudaEventRecord(start, stream), "event");
    // Staged through page-locked memory, so that the uploads run at the bus's speed.
    h_centers.reserve(3 * std::size_t(n));
    h_radii.reserve(n);
    std::memcpy(h_centers.get(), s.centers, 3 * std::size_t(n) * sizeof(float));
    std::memcpy(h_radii.get(), s.radii, std::size_t(n) * sizeof(float));
    d_centers.reserve(3 * std::size_t(n));
    d_radii.reserve(n);
    d_spheres.reserve(n);
    check_cuda(cudaMemcpyAsync(d_centers.get(), h_centers.get(), 3 * std::size_t(n) * sizeof(float),
                               cudaMemcpyHostToDevice, stream),
               "upload the centres");
    check_cuda(cudaMemcpyAsync(d_radii.get(), h_radii.get(), std::size_t(n) * sizeof(float),
                               cudaMemcpyHostToDevice, stream),
               "upload the radii");
    check_cuda(cudaMemcpyAsync(d_frame.get(), h_frame.get(), sizeof(bp::FrameState),
                               cudaMemcpyHostToDevice, stream),
               "upload the frame state");
    prepare(method, n);
    find_pairs_kernel(method, n);
    // Frames follow each other closely: download as many pairs as the last one had (and
    // a margin) at once, the rest only where there were more.
    const std::size_t guess =
        std::min<std::size_t>(d_pairs.capacity(), last_pairs + last_pairs / 4 + 1024);
    download(guess);
    const bp::FrameState& frame = h_frame.get()[1];
    if (frame.bad != bp::kNoBadSphere) {
      check_spheres(s);  // names the sphere and says what is wrong
      throw std::invalid_argument("GPU broad phase: sphere " + std::to_string(frame.bad) +
                                  " is not finite or has a negative radius");
    }
    std::size_t count = frame.pairs;
    if (count > d_pairs.capacity()) {
      // Overflow: the buffer grows to the exact count and the pair kernel runs again.
      grow_pairs(count);
      check_cuda(cudaMemsetAsync(&d_frame.get()->pairs, 0, sizeof(unsigned long long), stream),
                 "reset the pair count");
      find_pairs_kernel(method, n);
      ++stats.reruns;
      download(count);
      if (h_frame.get()[1].pairs != count) {
        throw std::runtime_error("GPU broad phase: the pair kernel found " +
                                 std::to_string(h_frame.get()[1].pairs) + " pairs, then " +
                                 std::to_string(count) + " (a bug)");
      }
    } else if (count > guess) {
      check_cuda(cudaMemcpyAsync(h_pairs.get() + guess, d_pairs.get() + guess,
                                 (count - guess) * sizeof(uint2), cudaMemcpyDeviceToHost, stream),
                 "download the pairs");
    }
    check_cuda(cudaEventRecord(stop, stream), "event");
    check_cuda(cudaEventSynchronize(stop), "the frame");
    pairs->resize(count);
    if (count > 0) std::memcpy(pairs->data(), h_pairs.get(), count * sizeof(uint2));
    last_pairs = count;
    float ms = 0;
    check_cuda(cudaEventElapsedTime(&ms, start, stop), "event time");
    stats.milliseconds = ms;
    stats.pairs = count;
    stats.pair_capacity = d_pairs.capacity();
    if (method == BroadPhaseMethod::kGpuSortSweep) stats.sweep_axis = bp::sweep_axis(frame, n);
    if (method == BroadPhaseMethod::kGpuGrid) stats.cell_size = bp::grid_frame(frame).cell;
  }
};

GpuBroadPhase::GpuBroadPhase() : impl_(std::make_unique<Impl>()) {}

GpuBroadPhase::~GpuBroadPhase() = default;

void GpuBroadPhase::find_pairs(BroadPhaseMethod method, const SphereArrays& spheres,
                               std::vector<SpherePair>* pairs) {
  impl_->find_pairs(method, spheres, pairs);
}

const GpuBroadPhaseStats& GpuBroadPhase::last_stats() const { return impl_->stats; }

std::string GpuBroadPhase::device_name() const { return impl_->device_name; }

}  // namespace gplanner
