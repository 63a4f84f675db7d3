// The GPU batch checker: the model uploaded once, batches cut into chunks under a memory
// cap, statistics, and dispatch to the traversal asked for (src/traversals/: basic,
// packet, balanced; they share the device functions of detail/query.h with the CPU
// batch checker).

#include "gplanner/collision_gpu/gpu_batch_checker.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gplanner/collision_gpu/model_view.h"
#include "gplanner/common/gpu_device.h"
#include "device_collision_model.cuh"
#include "gplanner/common/cuda_memory.cuh"
#include "traversals/balanced.cuh"
#include "traversals/basic.cuh"
#include "traversals/packet.cuh"

namespace gplanner {

using cuda::DeviceBuffer;
using traversals::check_cuda;

// The model, buffers and statistics on one device; made, used and freed with that device
// current (GpuDeviceScope).
struct GpuBatchChecker::Impl {
  int device = 0;
  GpuCheckerOptions options;
  FlatCollisionModel host;
  std::optional<DeviceCollisionModel> device_model;  // uploaded once a device is known
  CollisionModelView view{};                         // device_model's
  std::string device_name;
  std::size_t memory_cap = 0;
  std::mutex mutex;     // one call on the device at a time: the buffers below are shared
  GpuCheckStats stats;  // the call in progress, under `mutex`

  DeviceBuffer<float> configurations;
  DeviceBuffer<float> clearances;
  DeviceBuffer<std::uint8_t> verdicts;
  DeviceBuffer<traversals::DeviceTestCounts> counts;
  traversals::PacketTraversal packet;
  std::optional<traversals::BalancedTraversal> balanced;

  // Small batches: page-locked staging, so that every copy is queued with the kernels and
  // a call waits for the device once (kPinnedQueries rows at most).
  static constexpr std::size_t kPinnedQueries = 4096;
  cuda::PinnedBuffer<float> pinned_configurations, pinned_clearances;
  cuda::PinnedBuffer<std::uint8_t> pinned_verdicts;
  cuda::PinnedBuffer<traversals::DeviceTestCounts> pinned_counts;
  cuda::PinnedBuffer<traversals::BalancedState> pinned_state;
  std::optional<cuda::Event> start_event, stop_event;  // made with the model's upload

  Impl(const CollisionModel& model, const GpuCheckerOptions& o, int d)
      : device(d), options(o), host(model) {
    cudaDeviceProp properties{};
    check_cuda(cudaGetDeviceProperties(&properties, device), "cudaGetDeviceProperties");
    device_name = properties.name;
    std::size_t free_bytes = 0, total_bytes = 0;
    check_cuda(cudaMemGetInfo(&free_bytes, &total_bytes), "cudaMemGetInfo");
    memory_cap = options.memory_cap_bytes ? options.memory_cap_bytes : free_bytes / 2;

    view = device_model.emplace(host).view();
    counts.reserve(1);
    balanced.emplace(host, properties);
    pinned_configurations.reserve(kPinnedQueries * view.width);
    pinned_clearances.reserve(kPinnedQueries * std::max(1, view.link_count));
    pinned_verdicts.reserve(kPinnedQueries);
    pinned_counts.reserve(1);
    pinned_state.reserve(1);
    start_event.emplace();
    stop_event.emplace();
  }

  // Whether a batch of n goes the one-wait way: one kernel launch sequence, no rounds,
  // one chunk under the memory cap.
  bool is_small(std::size_t n) const {
    if (n > kPinnedQueries) return false;
    if (chunk_size(n, bytes_per_query(true), chunk_share()) < n) return false;
    if (options.traversal == Traversal::kBasic) return true;
    return options.traversal == Traversal::kBalanced &&
           n <= balanced->small_batch_up_to(options.warp_per_pair_up_to);
  }

  // A small batch: staged in page-locked memory, uploads, kernels and downloads queued on
  // the default stream, one wait at the end. False when the balanced traversal's jobs
  // overflowed (check() then runs the batch the usual way).
  bool check_small(const float* h_q, std::size_t n, std::uint8_t* h_verdicts,
                   const float* h_clearances) {
    const std::size_t width = view.width;
    const std::size_t links = static_cast<std::size_t>(view.link_count);
    CollisionModelView call_view = view;
    std::copy(h_q, h_q + n * width, pinned_configurations.get());
    configurations.reserve(std::max(n, kPinnedQueries) * width);
    verdicts.reserve(std::max(n, kPinnedQueries));
    if (options.traversal == Traversal::kBalanced) balanced->reserve(kPinnedQueries, memory_cap);
    check_cuda(cudaEventRecord(start_event->get()), "event");
    check_cuda(cudaMemcpyAsync(configurations.get(), pinned_configurations.get(),
                               n * width * sizeof(float), cudaMemcpyHostToDevice),
               "upload configurations");
    if (h_clearances) {
      std::copy(h_clearances, h_clearances + n * links, pinned_clearances.get());
      clearances.reserve(kPinnedQueries * links);
      check_cuda(cudaMemcpyAsync(clearances.get(), pinned_clearances.get(),
                                 n * links * sizeof(float), cudaMemcpyHostToDevice),
                 "upload clearances");
      call_view.clearances = clearances.get();
    }
    check_cuda(cudaMemsetAsync(counts.get(), 0, sizeof(traversals::DeviceTestCounts)), "memset");
    const int m = static_cast<int>(n);
    if (options.traversal == Traversal::kBasic) {
      traversals::run_basic(call_view, configurations.get(), m, verdicts.get(), counts.get());
    } else {
      balanced->enqueue_small(call_view, configurations.get(), m, verdicts.get(), counts.get(),
                              pinned_state.get());
    }
    check_cuda(cudaMemcpyAsync(pinned_verdicts.get(), verdicts.get(), n, cudaMemcpyDeviceToHost),
               "download verdicts");
    check_cuda(cudaMemcpyAsync(pinned_counts.get(), counts.get(),
                               sizeof(traversals::DeviceTestCounts), cudaMemcpyDeviceToHost),
               "read counters");
    check_cuda(cudaEventRecord(stop_event->get()), "event");
    check_cuda(cudaEventSynchronize(stop_event->get()), "wait for the small batch");
    if (options.traversal == Traversal::kBalanced &&
        !balanced->finish_small(*pinned_state.get(), &stats))
      return false;
    std::copy(pinned_verdicts.get(), pinned_verdicts.get() + n, h_verdicts);
    float ms = 0;
    check_cuda(cudaEventElapsedTime(&ms, start_event->get(), stop_event->get()), "event");
    stats.milliseconds = ms;
    stats.chunks = 1;
    stats.bv_tests = pinned_counts.get()->bv_tests;
    stats.triangle_tests = pinned_counts.get()->triangle_tests;
    return true;
  }

  // Bytes of chunk-sized buffers per query: its row, its clearances, its verdict and
  // counters.
  std::size_t bytes_per_query(bool with_clearances) const {
    const std::size_t links = with_clearances ? static_cast<std::size_t>(view.link_count) : 0;
    return (view.width + links) * sizeof(float) + 1 + 4 * sizeof(unsigned);
  }

  // The share of the memory cap a chunk's configurations and verdicts take: the balanced
  // traversal's queues take most of the rest.
  double chunk_share() const {
    return options.traversal == Traversal::kBalanced ? traversals::BalancedTraversal::kChunkShare
                                                     : 0.9;
  }

  // Queries per chunk under the memory cap, for `bytes_per_query` of chunk-sized buffers.
  std::size_t chunk_size(std::size_t n, std::size_t bytes_per_query, double share) const {
    const std::size_t fit = static_cast<std::size_t>(share * memory_cap) / bytes_per_query;
    return std::max<std::size_t>(1, std::min(n, fit));
  }

  void check(const float* h_q, std::size_t n, std::uint8_t* h_verdicts, const float* h_clearances) {
    stats = {};
    if (n == 0) return;
    if (is_small(n)) {
      if (check_small(h_q, n, h_verdicts, h_clearances)) return;
      stats = {};
    }
    CollisionModelView call_view = view;
    const bool is_balanced = options.traversal == Traversal::kBalanced;
    const std::size_t width = view.width;
    const std::size_t links = h_clearances ? static_cast<std::size_t>(view.link_count) : 0;
    std::size_t chunk = chunk_size(n, bytes_per_query(h_clearances != nullptr), chunk_share());
    if (is_balanced) balanced->reserve(chunk, memory_cap);
    configurations.reserve(chunk * width);
    if (h_clearances) {
      clearances.reserve(chunk * links);
      call_view.clearances = clearances.get();
    }
    verdicts.reserve(chunk);
    check_cuda(cudaMemset(counts.get(), 0, sizeof(traversals::DeviceTestCounts)), "memset");

    cudaEvent_t start = start_event->get(), stop = stop_event->get();
    check_cuda(cudaEventRecord(start), "event");
    std::size_t done = 0;
    while (done < n) {
      const std::size_t count = std::min(chunk, n - done);
      check_cuda(cudaMemcpy(configurations.get(), h_q + done * width, count * width * sizeof(float),
                            cudaMemcpyHostToDevice),
                 "upload configurations");
      if (h_clearances) {
        check_cuda(cudaMemcpy(clearances.get(), h_clearances + done * links,
                              count * links * sizeof(float), cudaMemcpyHostToDevice),
                   "upload clearances");
      }
      const int m = static_cast<int>(count);
      if (options.traversal == Traversal::kBasic) {
        traversals::run_basic(call_view, configurations.get(), m, verdicts.get(), counts.get());
      } else if (options.traversal == Traversal::kPacket) {
        packet.run(call_view, configurations.get(), m, verdicts.get(), counts.get());
      } else if (!balanced->run(call_view, configurations.get(), m, verdicts.get(), counts.get(),
                                options.warp_per_pair_up_to, &stats)) {
        if (chunk == 1)
          throw std::runtime_error("balanced traversal: one query needs more jobs than fit");
        chunk = std::max<std::size_t>(1, chunk / 2);
        continue;  // the same queries again, fewer at a time
      }
      check_cuda(cudaMemcpy(h_verdicts + done, verdicts.get(), count, cudaMemcpyDeviceToHost),
                 "download verdicts");
      done += count;
      ++stats.chunks;
    }
    check_cuda(cudaEventRecord(stop), "event");
    check_cuda(cudaEventSynchronize(stop), "event");
    float ms = 0;
    check_cuda(cudaEventElapsedTime(&ms, start, stop), "event");
    traversals::DeviceTestCounts c;
    check_cuda(cudaMemcpy(&c, counts.get(), sizeof(c), cudaMemcpyDeviceToHost), "read counters");
    stats.milliseconds = ms;
    stats.bv_tests = c.bv_tests;
    stats.triangle_tests = c.triangle_tests;
  }
};

namespace {

// The devices a checker runs on: the one asked for, or every one with kAllDevices;
// throws saying why where that cannot be.
std::vector<int> devices_of(const GpuCheckerOptions& options) {
  std::string reason;
  const int count = gpu_device_count(&reason);
  if (count == 0) throw std::runtime_error("no usable GPU: " + reason);
  if (options.device == GpuCheckerOptions::kAllDevices) {
    std::vector<int> all(count);
    for (int d = 0; d < count; ++d) all[d] = d;
    return all;
  }
  const GpuDevice device = query_gpu_device(options.device);
  if (!device.available) throw std::runtime_error(device.reason);
  return {options.device};
}

}  // namespace

GpuBatchChecker::GpuBatchChecker(const CollisionModel& model, const GpuCheckerOptions& options) {
  try {
    for (const int device : devices_of(options)) {
      const GpuDeviceScope scope(device);
      impls_.push_back(std::make_unique<Impl>(model, options, device));
    }
  } catch (...) {
    release();  // the destructor does not run for a checker not made
    throw;
  }
}

GpuBatchChecker::~GpuBatchChecker() { release(); }

void GpuBatchChecker::release() {
  for (std::unique_ptr<Impl>& impl : impls_) {
    // Where the device cannot be made current (the runtime unloading at the process's
    // exit), the buffers are freed as they can be: a destructor throws nothing.
    std::optional<GpuDeviceScope> scope;
    try {
      scope.emplace(impl->device);
    } catch (const std::exception&) {
    }
    impl.reset();
  }
  impls_.clear();
}

void GpuBatchChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
                            const float* clearances) {
  const auto check_on = [&](Impl& impl, std::size_t first, std::size_t count) {
    const std::lock_guard<std::mutex> lock(impl.mutex);
    const GpuDeviceScope scope(impl.device);
    const std::size_t links = clearances ? static_cast<std::size_t>(impl.view.link_count) : 0;
    impl.check(configurations + first * impl.view.width, count, verdicts + first,
               clearances ? clearances + first * links : nullptr);
    return impl.stats;
  };
  if (impls_.size() == 1 || n < kSplitBatchesFrom) {
    const GpuCheckStats stats = check_on(*impls_.front(), 0, n);
    const std::lock_guard<std::mutex> lock(stats_mutex_);
    last_stats_ = stats;
    return;
  }
  // One contiguous part per device, each checked on a thread of its own (a call waits
  // for its device); the first part on the calling thread.
  const std::size_t parts = impls_.size();
  std::vector<GpuCheckStats> stats(parts);
  std::vector<std::exception_ptr> errors(parts);
  const auto part = [&](std::size_t p) {
    const std::size_t first = n * p / parts, end = n * (p + 1) / parts;
    try {
      stats[p] = check_on(*impls_[p], first, end - first);
    } catch (...) {
      errors[p] = std::current_exception();
    }
  };
  std::vector<std::thread> threads;
  try {
    for (std::size_t p = 1; p < parts; ++p) threads.emplace_back(part, p);
  } catch (...) {  // no thread to be had: the parts started end first
    for (std::thread& thread : threads) thread.join();
    throw;
  }
  part(0);
  for (std::thread& thread : threads) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
  GpuCheckStats whole = stats.front();
  for (std::size_t p = 1; p < parts; ++p) {
    whole.milliseconds = std::max(whole.milliseconds, stats[p].milliseconds);
    whole.chunks += stats[p].chunks;
    whole.rounds += stats[p].rounds;
    whole.finished_tasks += stats[p].finished_tasks;
    whole.jobs += stats[p].jobs;
    whole.bv_tests += stats[p].bv_tests;
    whole.triangle_tests += stats[p].triangle_tests;
  }
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  last_stats_ = whole;
}

GpuCheckStats GpuBatchChecker::last_stats() const {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  return last_stats_;
}

std::string GpuBatchChecker::device_name() const {
  const std::string& name = impls_.front()->device_name;
  if (impls_.size() == 1) return name;
  bool same = true;
  for (const auto& impl : impls_) same = same && impl->device_name == name;
  if (same) return std::to_string(impls_.size()) + " x " + name;
  std::string names;
  for (const auto& impl : impls_) names += (names.empty() ? "" : ", ") + impl->device_name;
  return names;
}

std::vector<int> GpuBatchChecker::devices() const {
  std::vector<int> devices;
  for (const auto& impl : impls_) devices.push_back(impl->device);
  return devices;
}

}  // namespace gplanner
