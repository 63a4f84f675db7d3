#pragma once
// The `gpu` backend: the scene's collision model on the GPU, with a chosen traversal, and
// the same core on host threads for calls too small to pay for a GPU call.
//
// Calls of every size: a GPU call costs tens of microseconds whatever its size (uploads,
// launches, one synchronisation), while the core on one host thread checks a rigid
// robot's state in microseconds. So small calls (OMPL's planners check one state or one
// short motion at a time) are answered on the calling thread, middle-sized ones on the
// host's thread pool, and large ones on the GPU; the two crossovers are measured on the
// scene when the checker is made (HostCallRouting). The host and the GPU run the same
// core (BVHs, leaf tests, tolerance band), so a configuration's verdict does not depend
// on where it was checked beyond float rounding inside the band.
//
// Calls from any number of threads are safe. Host calls run in parallel; GPU calls take
// turns on the device (one call's device work at a time, under a lock: GpuBatchChecker).

#include <atomic>
#include <memory>
#include <vector>

#include "gplanner/collision_gpu/cpu_batch_checker.h"
#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

// Where calls of each size go, and the measurements that chose it.
struct HostCallRouting {
  std::size_t calling_thread_up_to = 0;  // calls of up to this many: the calling thread
  std::size_t host_threads_up_to = 0;    // up to this many: the host's thread pool
  bool measured = false;                 // false: set by GpuCheckerOptions::host_calls_up_to
  // What a GPU call costs by itself, in configurations: its fixed cost (a call of one
  // configuration) over the cost of one more (between calls of 1,024 and 4,096), within
  // [256, 65,536]; 8,192 where not measured. configurations_per_call_cost() answers it.
  std::size_t call_cost = 8192;
  // The measurements (seconds per call), at the sizes measured.
  double host_seconds_per_configuration = 0;  // one thread, the scene's free uniform samples
  std::vector<std::size_t> sizes;             // shape [k]
  std::vector<double> gpu_seconds;            // shape [k]: a GPU call of sizes[i] (median)
  // shape [k]: a host call of sizes[i] (median; 1e30 where not timed: the sizes after
  // one at which the host took twice the GPU's time)
  std::vector<double> host_threads_seconds;
  // shape [k]: the same call on the calling thread (median; 1e30 where not timed: the
  // sizes after one at which it took twice the time of the faster of the pool and the GPU)
  std::vector<double> calling_thread_seconds;
};

class GpuChecker : public CollisionChecker {
 public:
  // Throws std::runtime_error saying why when no GPU can be used. host_threads: threads
  // of host calls (0: all cores).
  GpuChecker(const Scene& scene, const GpuCheckerOptions& options, int host_threads = 0);
  ~GpuChecker() override;

  std::string backend() const override { return "gpu"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override;
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override;
  // Measured on the scene with the routing (HostCallRouting::call_cost): a Panda's call on
  // an H200 costs about 0.12 ms plus 0.06 ms per 1,000 configurations, about 2,000.
  std::size_t configurations_per_call_cost() const override { return routing_.call_cost; }
  // Calls the host answers: no GPU call's fixed cost (host_calls_up_to()).
  std::size_t cheap_calls_up_to() const override { return host_calls_up_to(); }
  CollisionChecker* host_checker() override { return &host_only_; }
  std::size_t device_calls() const override { return device_calls_.load(); }
  int gpu_device() const override { return gpu_.devices().front(); }

  // Of the last check() on the GPU to finish (calls answered on the host leave it as is).
  GpuCheckStats last_stats() const { return gpu_.last_stats(); }
  std::string device_name() const { return gpu_.device_name(); }
  std::vector<int> devices() const { return gpu_.devices(); }
  Traversal traversal() const { return traversal_; }
  const HostCallRouting& routing() const { return routing_; }
  // Calls of up to this many configurations go to the host: routing().host_threads_up_to,
  // or, where the routing was measured, the largest size (a power of two, up to it) at
  // which the host's measured time, scaled by host_cost_ratio(), beats the GPU's (one
  // configuration at least, where the routing sent that to the host).
  std::size_t host_calls_up_to() const;
  // What the host's calls have cost per configuration, over what the routing measured
  // on the scene's free uniform samples: a running mean over the host's calls (a plan's
  // motions run near obstacles, where a configuration costs the host several times
  // more), from 1.
  double host_cost_ratio() const { return host_cost_ratio_.load(std::memory_order_relaxed); }

 private:
  // The host core, for host_checker(): calls routed as route() routes them, except that
  // those the GPU would take go to the thread pool.
  class HostOnly : public CollisionChecker {
   public:
    explicit HostOnly(GpuChecker* owner) : owner_(owner) {}
    std::string backend() const override { return "gpu"; }
    void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override {
      owner_->check_on_host(configurations, n, nullptr, verdicts);
    }
    void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                          std::uint8_t* verdicts) override {
      owner_->check_on_host(configurations, n, clearances, verdicts);
    }

   private:
    GpuChecker* owner_;
  };

  GpuChecker(const CollisionModel& model, const Scene& scene, const GpuCheckerOptions& options,
             int host_threads);
  void route(const float* configurations, std::size_t n, const float* clearances,
             std::uint8_t* verdicts);
  // The calling thread for calls of up to routing_.calling_thread_up_to, else the pool.
  void check_on_host(const float* configurations, std::size_t n, const float* clearances,
                     std::uint8_t* verdicts);
  void measure_routing(const Scene& scene);

  Traversal traversal_;
  GpuBatchChecker gpu_;
  CpuBatchChecker host_;
  int host_threads_;
  HostCallRouting routing_;
  HostOnly host_only_{this};
  std::atomic<std::size_t> device_calls_{0};
  std::atomic<double> host_cost_ratio_{1.0};
};

}  // namespace gplanner
