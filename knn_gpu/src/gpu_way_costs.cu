// GpuWayCosts: rounds of Bellman-Ford over the roadmap's rows (gpu_way_costs.h).

#include <cuda_runtime.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include "gplanner/common/cuda_memory.cuh"
#include "gplanner/common/gpu_device.h"
#include "gplanner/knn_gpu/gpu_way_costs.h"

namespace gplanner {
namespace {

void check_cuda(cudaError_t status, const char* what) {
  cuda::check(status, "GPU way costs: CUDA", what);
}

using cuda::DeviceBuffer;
using cuda::PinnedBuffer;

constexpr int kBlock = 256;
// Rounds launched before their flags are read back: a first group, then doubling up to
// the largest (a round that changes nothing after the last change costs one pass over
// the rows, about as much as reading the flags back). The first group is kFirstGroup, or
// after a computation kAfterLast rounds more than it took: a roadmap's computations take
// about as many rounds each (lazy PRM's on the piano's roadmaps of 8,000 to 32,000
// milestones: 17 to 25, where groups of 16 then 32 launched 48).
constexpr int kFirstGroup = 16, kLargestGroup = 64, kAfterLast = 2;
// Threads sharing a vertex's row in a round (round_kernel). A thread a vertex took 30 to
// 70 us a round on the piano's roadmaps (host timers around the usability's upload and
// the rounds), its loads one after another. Measured (H200, the four rigid bodies'
// shipped scenes, seeds 1 to 5 twice, in turn; the same costs and paths): 4 threads
// 1.04x, 8 1.05x, 16 1.07x sooner plans (geometric means), the search stage 11 % shorter
// at 16. Lazy PRM's rows hold about 24 entries.
constexpr int kLanesPerVertex = 16;

using cuda::blocks_for;

__global__ void start_kernel(std::uint32_t n, std::uint32_t target, double infinity, double* cost,
                             std::uint8_t* active) {
  const std::uint32_t v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v >= n) return;
  cost[v] = v == target ? 0.0 : infinity;
  active[v] = v == target;
}

// One round: each vertex with a neighbour whose cost changed in the last round takes the
// least of those neighbours' costs plus the edge's length where that is less than its
// own. (Costs are read as other threads write them: an 8-byte load sees the old or the
// new cost, both the cost of a way; a neighbour lowered in this round is active in the
// next.) changed[0] is set where any cost fell. kLanes threads share a vertex's row, each
// taking every kLanes-th entry, and the least of theirs is the vertex's: a minimum is the
// same in any order, so the costs are those of a thread a vertex.
template <int kLanes>
__global__ void round_kernel(std::uint32_t n, double infinity, const std::size_t* first,
                             const WayEdge* rows, const std::uint8_t* usable, double* cost,
                             const std::uint8_t* active, std::uint8_t* active_next, int* changed) {
  static_assert(kLanes > 0 && 32 % kLanes == 0 && kBlock % 32 == 0,
                "a vertex's lanes lie within one warp");
  const std::size_t thread = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  const std::size_t v = thread / kLanes;
  const int lane = static_cast<int>(thread % kLanes);
  double best = infinity;
  if (v < n) {
    for (std::size_t i = first[v] + lane, end = first[v + 1]; i < end; i += kLanes) {
      const WayEdge entry = rows[i];
      if (!active[entry.other] || !usable[entry.edge]) continue;
      const double through = cost[entry.other] + static_cast<double>(entry.length);
      if (through < best) best = through;
    }
  }
  // Every lane of the warp takes part (a vertex's lanes lie within one warp).
  for (int offset = kLanes / 2; offset > 0; offset /= 2)
    best = fmin(best, __shfl_down_sync(0xffffffffu, best, offset, kLanes));
  if (v >= n || lane != 0) return;
  const bool lowered = best < cost[v];  // only this thread writes cost[v]
  if (lowered) {
    cost[v] = best;
    *changed = 1;
  }
  active_next[v] = lowered;
}

// Each vertex's first edge to a neighbour before it in (cost, index) order whose cost
// plus the edge's length is its own; orphans counted.
__global__ void via_kernel(std::uint32_t n, std::uint32_t target, double infinity,
                           const std::size_t* first, const WayEdge* rows,
                           const std::uint8_t* usable, const double* cost, std::uint32_t* via,
                           int* orphans) {
  const std::uint32_t v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v >= n) return;
  std::uint32_t chosen = GpuWayCosts::kNoEdge;
  const double c = cost[v];
  if (v != target && c < infinity) {
    for (std::size_t i = first[v], end = first[v + 1]; i < end; ++i) {
      const WayEdge entry = rows[i];
      if (!usable[entry.edge]) continue;
      const double cu = cost[entry.other];
      if (cu + static_cast<double>(entry.length) == c && (cu < c || (cu == c && entry.other < v))) {
        chosen = entry.edge;
        break;
      }
    }
    if (chosen == GpuWayCosts::kNoEdge) atomicAdd(orphans, 1);
  }
  via[v] = chosen;
}

}  // namespace

struct GpuWayCosts::Impl {
  using Outcome = GpuWayCosts::Outcome;
  int device = 0;
  std::size_t vertices = 0, edges = 0;
  DeviceBuffer<std::size_t> first;
  DeviceBuffer<WayEdge> rows;
  DeviceBuffer<std::uint8_t> usable, active, active_next;
  DeviceBuffer<double> cost;
  DeviceBuffer<std::uint32_t> via;
  DeviceBuffer<int> flags;  // kLargestGroup rounds' changed flags, then the orphans
  PinnedBuffer<int> host_flags;
  std::size_t calls = 0, last_rounds = 0;
  std::uint64_t key = 0;

  void launch_round(std::uint32_t n, const std::uint8_t* from, std::uint8_t* to, int* changed) {
    round_kernel<kLanesPerVertex><<<blocks_for(std::size_t(n) * kLanesPerVertex, kBlock), kBlock>>>(
        n, std::numeric_limits<double>::infinity(), first.get(), rows.get(), usable.get(),
        cost.get(), from, to, changed);
  }

  void set_roadmap(const std::size_t* h_first, std::size_t n, const WayEdge* h_rows,
                   std::size_t e) {
    if (n >= GpuWayCosts::kNoEdge || e >= GpuWayCosts::kNoEdge)
      throw std::invalid_argument("GPU way costs: more than 2^32 - 1 vertices or edges");
    vertices = n;
    edges = e;
    first.reserve(n + 1);
    rows.reserve(h_first[n]);
    check_cuda(
        cudaMemcpy(first.get(), h_first, (n + 1) * sizeof(std::size_t), cudaMemcpyHostToDevice),
        "upload the rows' starts");
    if (h_first[n] > 0) {
      check_cuda(
          cudaMemcpy(rows.get(), h_rows, h_first[n] * sizeof(WayEdge), cudaMemcpyHostToDevice),
          "upload the rows");
    }
    usable.reserve(e);
    active.reserve(n);
    active_next.reserve(n);
    cost.reserve(n);
    via.reserve(n);
    flags.reserve(kLargestGroup + 1);
    host_flags.reserve(kLargestGroup + 1);
  }

  Outcome compute(std::uint32_t target, const std::uint8_t* h_usable, double* h_cost,
                  std::uint32_t* h_via, const std::function<bool()>& should_stop) {
    ++calls;
    if (target >= vertices) throw std::invalid_argument("GPU way costs: target out of range");
    const auto n = static_cast<std::uint32_t>(vertices);
    if (edges > 0) {
      check_cuda(cudaMemcpyAsync(usable.get(), h_usable, edges, cudaMemcpyHostToDevice),
                 "upload usability");
    }
    const double infinity = std::numeric_limits<double>::infinity();
    start_kernel<<<blocks_for(n, kBlock), kBlock>>>(n, target, infinity, cost.get(), active.get());
    check_cuda(cudaGetLastError(), "start kernel");
    std::uint8_t* from = active.get();
    std::uint8_t* to = active_next.get();
    const int first_group =
        last_rounds > 0
            ? static_cast<int>(std::min<std::size_t>(last_rounds + kAfterLast, kLargestGroup))
            : kFirstGroup;
    last_rounds = 0;
    for (int group = first_group;; group = std::min(2 * group, kLargestGroup)) {
      if (should_stop && should_stop()) return Outcome::kStopped;
      check_cuda(cudaMemsetAsync(flags.get(), 0, group * sizeof(int)), "clear flags");
      for (int r = 0; r < group; ++r) {
        launch_round(n, from, to, flags.get() + r);
        std::swap(from, to);
      }
      check_cuda(cudaGetLastError(), "round kernel");
      check_cuda(
          cudaMemcpy(host_flags.get(), flags.get(), group * sizeof(int), cudaMemcpyDeviceToHost),
          "read flags");
      int last_change = -1;
      for (int r = 0; r < group; ++r)
        if (host_flags.get()[r]) last_change = r;
      last_rounds += static_cast<std::size_t>(last_change + 1);
      if (last_change < group - 1) break;
    }
    int* orphans = flags.get() + kLargestGroup;
    check_cuda(cudaMemsetAsync(orphans, 0, sizeof(int)), "clear orphans");
    via_kernel<<<blocks_for(n, kBlock), kBlock>>>(n, target, infinity, first.get(), rows.get(),
                                                  usable.get(), cost.get(), via.get(), orphans);
    check_cuda(cudaGetLastError(), "via kernel");
    check_cuda(cudaMemcpy(h_cost, cost.get(), n * sizeof(double), cudaMemcpyDeviceToHost),
               "download costs");
    check_cuda(cudaMemcpy(h_via, via.get(), n * sizeof(std::uint32_t), cudaMemcpyDeviceToHost),
               "download first edges");
    check_cuda(cudaMemcpy(host_flags.get(), orphans, sizeof(int), cudaMemcpyDeviceToHost),
               "read orphans");
    return host_flags.get()[0] == 0 ? Outcome::kDone : Outcome::kNoFirstEdge;
  }
};

bool gpu_way_costs_available(std::string* reason) {
  const GpuDevice gpu = query_gpu_device(0);
  if (!gpu.available && reason) *reason = gpu.reason;
  return gpu.available;
}

GpuWayCosts::GpuWayCosts(int device) {
  const GpuDevice gpu = query_gpu_device(device);
  if (!gpu.available) throw std::runtime_error("GPU way costs: no usable GPU (" + gpu.reason + ")");
  const GpuDeviceScope scope(device);
  impl_ = std::make_unique<Impl>();
  impl_->device = device;
}

GpuWayCosts::~GpuWayCosts() {
  std::optional<GpuDeviceScope> scope;
  try {
    scope.emplace(impl_->device);
  } catch (const std::exception&) {
  }
  impl_.reset();
}

void GpuWayCosts::set_roadmap(std::uint64_t key, const std::size_t* first, std::size_t vertices,
                              const WayEdge* rows, std::size_t edges) {
  const GpuDeviceScope scope(impl_->device);
  impl_->key = 0;  // none while uploading: a failed upload holds no roadmap
  impl_->set_roadmap(first, vertices, rows, edges);
  impl_->key = key;
}

std::uint64_t GpuWayCosts::roadmap_key() const { return impl_->key; }

GpuWayCosts::Outcome GpuWayCosts::compute(std::uint32_t target, const std::uint8_t* usable,
                                          double* cost, std::uint32_t* via,
                                          const std::function<bool()>& should_stop) {
  const GpuDeviceScope scope(impl_->device);
  return impl_->compute(target, usable, cost, via, should_stop);
}

std::size_t GpuWayCosts::calls() const { return impl_->calls; }
std::size_t GpuWayCosts::last_rounds() const { return impl_->last_rounds; }

}  // namespace gplanner
