// The GPU sphere broad phase: buffers kept between frames, the launch sequence of each
// method, and the pair buffer that grows to the exact count when it overflows. Kernels are
// in gpu_broad_phase_device.cuh.

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cub/device/device_radix_sort.cuh>
#include <stdexcept>
#include <optional>
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

// Where a frame's data lie in its transfer buffer (byte offsets): the centres (shape
// [n, 3]) from 0, the radii (shape [n]), the frame state, the pairs (shape [capacity]).
// The upload is everything before the pairs, the download the frame state and the pairs.
struct IoLayout {
  std::size_t radii, frame, pairs, bytes;
};

// Large uploads go in chunks of this many bytes (staging and transfer overlapping).
constexpr std::size_t kUploadChunk = std::size_t(1) << 20;

std::size_t aligned(std::size_t bytes) { return (bytes + 15) / 16 * 16; }

IoLayout io_layout(unsigned n, std::size_t capacity) {
  IoLayout io;
  io.radii = 3 * std::size_t(n) * sizeof(float);
  io.frame = aligned(io.radii + std::size_t(n) * sizeof(float));
  io.pairs = io.frame + aligned(sizeof(bp::FrameState));
  io.bytes = io.pairs + capacity * sizeof(uint2);
  return io;
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
  std::optional<cuda::Stream> owned_stream;  // made once a device is known to be there
  cudaStream_t stream = nullptr;              // owned_stream's

  // One frame's transfers, one upload and one download, through one buffer laid out as
  // IoLayout says (the same on the host, page-locked, and on the device).
  PinnedBuffer<unsigned char> h_io;
  DeviceBuffer<unsigned char> d_io;
  IoLayout io{};
  DeviceBuffer<float4> d_spheres;                              // shape [n]: x, y, z, r
  DeviceBuffer<float4> d_sorted;                               // shape [n]: in sweep or cell order
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
  std::size_t pair_capacity = 4096;  // pairs the buffer holds: the largest count seen
  std::size_t last_pairs = 0;        // the previous frame's count: what to download at once

  float* d_centers() const { return reinterpret_cast<float*>(d_io.get()); }
  float* d_radii() const { return reinterpret_cast<float*>(d_io.get() + io.radii); }
  bp::FrameState* d_frame() const {
    return reinterpret_cast<bp::FrameState*>(d_io.get() + io.frame);
  }
  uint2* d_pairs() const { return reinterpret_cast<uint2*>(d_io.get() + io.pairs); }
  const bp::FrameState& h_frame() const {
    return *reinterpret_cast<const bp::FrameState*>(h_io.get() + io.frame);
  }

  Impl() {
    const GpuDevice device = query_gpu_device();
    if (!device.available) {
      throw std::runtime_error("GPU broad phase: no usable GPU (" + device.reason +
                               "); use all_pairs_cpu() or sort_sweep_cpu()");
    }
    device_name = device.name;
    stream = owned_stream.emplace().get();
  }

  void launched(const char* what) {
    check_cuda(cudaGetLastError(), what);
    ++stats.kernels;
  }

  bp::PairOutput pair_output() const { return {d_pairs(), pair_capacity, &d_frame()->pairs}; }

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

  // Everything before the pair kernel: packing, extents, sorting, the tree.
  void prepare(BroadPhaseMethod method, unsigned n) {
    const unsigned blocks = blocks_for(n);
    if (method == BroadPhaseMethod::kGpuAllPairs) return;  // reads and checks the upload itself
    d_spheres.reserve(n);
    bp::pack_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_centers(), d_radii(), n, d_spheres.get(),
                                                       d_frame());
    launched("pack");
    d_sorted.reserve(n);
    d_ids.reserve(n);
    d_sorted_ids.reserve(n);
    if (method == BroadPhaseMethod::kGpuSortSweep) {
      d_keys32.reserve(n);
      d_sorted_keys32.reserve(n);
      d_low.reserve(n);
      d_high.reserve(n);
      bp::sweep_keys_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame(),
                                                               d_keys32.get(), d_ids.get());
      launched("sweep keys");
      sort(d_keys32.get(), d_sorted_keys32.get(), n, 32);
      bp::sweep_gather_kernel<<<blocks, bp::kBlock, 0, stream>>>(
          d_spheres.get(), d_sorted_keys32.get(), d_sorted_ids.get(), n, d_frame(), d_sorted.get(),
          d_low.get(), d_high.get());
      launched("sweep gather");
    } else if (method == BroadPhaseMethod::kGpuLbvh) {
      d_keys32.reserve(n);
      d_sorted_keys32.reserve(n);
      d_nodes.reserve(n - 1);
      d_node_boxes.reserve(n - 1);
      d_leaf_boxes.reserve(n);
      d_parents.reserve(2 * std::size_t(n) - 1);
      d_flags.reserve(n - 1);
      bp::lbvh_codes_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame(),
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
      bp::grid_keys_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), n, d_frame(),
                                                              d_keys64.get(), d_ids.get());
      launched("grid keys");
      sort(d_keys64.get(), d_sorted_keys64.get(), n, 3 * detail::grid::kCellBits);
      bp::grid_gather_kernel<<<blocks, bp::kBlock, 0, stream>>>(d_spheres.get(), d_sorted_ids.get(),
                                                                n, d_sorted.get());
      launched("grid gather");
    }
  }

  void find_pairs_kernel(BroadPhaseMethod method, unsigned n) {
    const unsigned blocks = blocks_for(n);
    if (method == BroadPhaseMethod::kGpuAllPairs) {
      bp::all_pairs_kernel<<<dim3(blocks, blocks), bp::kBlock, 0, stream>>>(
          d_centers(), d_radii(), n, d_frame(), pair_output());
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

  // Room for the inputs of n spheres and `capacity` pairs, with a clear error where the
  // device has none.
  void reserve_io(unsigned n, std::size_t capacity) {
    io = io_layout(n, capacity);
    if (io.bytes > d_io.capacity()) {
      std::size_t free_bytes = 0, total_bytes = 0;
      check_cuda(cudaMemGetInfo(&free_bytes, &total_bytes), "free memory");
      if (io.bytes > free_bytes + d_io.capacity()) {
        throw std::runtime_error("GPU broad phase: " + std::to_string(capacity) + " pairs (" +
                                 std::to_string((capacity * sizeof(uint2)) >> 20) +
                                 " MiB) do not fit the " + std::to_string(free_bytes >> 20) +
                                 " MiB free on the device; use fewer or smaller spheres");
      }
    }
    d_io.reserve(io.bytes);
    h_io.reserve(io.bytes);
  }

  // Bytes [at, at + bytes) of the transfer buffer to the device.
  void upload(std::size_t at, std::size_t bytes) {
    check_cuda(
        cudaMemcpyAsync(d_io.get() + at, h_io.get() + at, bytes, cudaMemcpyHostToDevice, stream),
        "upload the spheres");
  }

  // `bytes` from `source` staged at `at` and uploaded, a chunk at a time.
  void stage_and_upload(std::size_t at, const void* source, std::size_t bytes) {
    for (std::size_t done = 0; done < bytes; done += kUploadChunk) {
      const std::size_t part = std::min(kUploadChunk, bytes - done);
      std::memcpy(h_io.get() + at + done, static_cast<const unsigned char*>(source) + done, part);
      upload(at + done, part);
    }
  }

  // One attempt at the frame with the pair buffer at `pair_capacity`: upload, kernels,
  // download of the frame state and of the pairs where they fit. Returns the pairs found
  // (more than pair_capacity: the buffer overflowed, and only its part was kept).
  std::size_t run_frame(BroadPhaseMethod method, const SphereArrays& s) {
    const unsigned n = static_cast<unsigned>(s.n);
    reserve_io(n, pair_capacity);
    // Staged in page-locked memory, so that the uploads run at the bus's speed: one upload
    // for a small frame; a large one a chunk at a time, each chunk's upload overlapping the
    // staging of the next.
    const bp::FrameState initial = initial_frame();
    std::memcpy(h_io.get() + io.frame, &initial, sizeof initial);
    if (io.pairs <= kUploadChunk) {
      std::memcpy(h_io.get(), s.centers, 3 * std::size_t(n) * sizeof(float));
      std::memcpy(h_io.get() + io.radii, s.radii, std::size_t(n) * sizeof(float));
      upload(0, io.pairs);
    } else {
      stage_and_upload(0, s.centers, 3 * std::size_t(n) * sizeof(float));
      stage_and_upload(io.radii, s.radii, std::size_t(n) * sizeof(float));
      upload(io.frame, sizeof initial);
    }
    prepare(method, n);
    find_pairs_kernel(method, n);
    // Frames follow each other closely: the frame state and as many pairs as the last
    // frame had (and a margin) come down at once, the rest only where there were more.
    const std::size_t guess =
        std::min<std::size_t>(pair_capacity, last_pairs + last_pairs / 4 + 1024);
    check_cuda(cudaMemcpyAsync(h_io.get() + io.frame, d_io.get() + io.frame,
                               io.pairs - io.frame + guess * sizeof(uint2), cudaMemcpyDeviceToHost,
                               stream),
               "download the pairs");
    check_cuda(cudaStreamSynchronize(stream), "the frame's kernels");
    const std::size_t count = h_frame().pairs;
    if (count > guess && count <= pair_capacity) {
      check_cuda(cudaMemcpyAsync(h_io.get() + io.pairs + guess * sizeof(uint2),
                                 d_io.get() + io.pairs + guess * sizeof(uint2),
                                 (count - guess) * sizeof(uint2), cudaMemcpyDeviceToHost, stream),
                 "download the pairs");
    }
    return count;
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
                                  " spheres; use gpu-grid, gpu-lbvh or gpu-sort-sweep");
    }
    stats = GpuBroadPhaseStats{};
    pairs->clear();
    if (n < 2) {
      check_spheres(s);  // nothing to launch: checked here
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    std::size_t count = run_frame(method, s);
    if (h_frame().bad == bp::kNoBadSphere && count > pair_capacity) {
      // Overflow: the buffer grows to the exact count and the frame runs again.
      pair_capacity = count;
      ++stats.reruns;
      const std::size_t again = run_frame(method, s);
      if (again != count) {
        throw std::runtime_error("GPU broad phase: the pair kernel found " + std::to_string(count) +
                                 " pairs, then " + std::to_string(again) + " (a bug)");
      }
    }
    check_cuda(cudaStreamSynchronize(stream), "the frame");
    const bp::FrameState& frame = h_frame();
    if (frame.bad != bp::kNoBadSphere) {
      check_spheres(s);  // names the sphere and says what is wrong
      throw std::invalid_argument("GPU broad phase: sphere " + std::to_string(frame.bad) +
                                  " is not finite or has a negative radius");
    }
    pairs->resize(count);
    if (count > 0) std::memcpy(pairs->data(), h_io.get() + io.pairs, count * sizeof(uint2));
    last_pairs = count;
    stats.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.pairs = count;
    stats.pair_capacity = pair_capacity;
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
