#pragma once
// The batch collision checker on the GPU: configurations [n, width] in, one verdict
// each out, with one of three traversals sharing BVHs, box tests, leaf tests and early
// exit (see DESIGN.md, "Collision core"). Plain C++: no CUDA headers.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "gplanner/collision_gpu/collision_model.h"

namespace gplanner {

enum class Traversal {
  kBasic,     // one thread per query, private stack
  kPacket,    // k-means clustered queries, one warp per packet on one shared stack
  kBalanced,  // one task per BV-pair or triangle test, in a global queue
};

const char* traversal_name(Traversal traversal);
// Parses "basic", "packet" or "balanced"; false for anything else.
bool parse_traversal(const std::string& name, Traversal* traversal);

struct GpuCheckerOptions {
  Traversal traversal = Traversal::kBalanced;
  // Device memory the checker may use for one chunk of queries (configurations,
  // verdicts, work queues); 0: half of the free memory. Larger batches are chunked.
  std::size_t memory_cap_bytes = 0;
  // balanced: batches of up to this many queries are traversed a warp per body pair in
  // one kernel (the pair's node pairs tested 32 at a time) instead of in rounds of
  // tasks; a small batch's time is the latency of its longest chain of tests, which
  // rounds of launches lengthen. 0: always rounds. kAuto, as measured on an H100
  // (benchmarks/history/issue4_planning.md) and an H200 (issue 33): for robots with more
  // link and pair tests than a warp has lanes (many small body pairs), up to 4,096 queries
  // where they have up to 40 checked bodies (an arm), 1,024 from 160 (a PR2 arm, a
  // humanoid), in proportion between; up to 10 for the others (whose one body pair with
  // the environment the rounds spread over more than a warp).
  static constexpr std::size_t kAuto = ~std::size_t(0);
  std::size_t warp_per_pair_up_to = kAuto;
  // For the planner's gpu backend (GpuChecker; GpuBatchChecker itself always uses the
  // GPU): calls of up to this many configurations are answered by the same core on host
  // threads, the calling thread first, where that is faster than a GPU call. kAuto: up to
  // the crossovers measured on the scene when the checker is made; 0: every call on the
  // GPU (what tests of the kernels and the query tables ask for).
  std::size_t host_calls_up_to = kAuto;
  // The CUDA device the checker runs on, numbered among those this process sees
  // (CUDA_VISIBLE_DEVICES). kAllDevices: every one the process sees, the model on each;
  // a batch of at least kSplitBatchesFrom configurations is then cut into one part per
  // device, checked at the same time, and smaller ones go to the first device.
  static constexpr int kAllDevices = -1;
  int device = 0;
};

// Batches of at least this many configurations are split across the devices of a
// checker on kAllDevices: below it, a second device's call saves less than it costs (a
// GPU call of thousands of configurations costs about its fixed cost; docs/design.md).
inline constexpr std::size_t kSplitBatchesFrom = 32768;

// What a check() did.
struct GpuCheckStats {
  double milliseconds = 0;  // GPU time of the whole batch (events around all chunks)
  std::size_t chunks = 0;
  std::size_t rounds = 0;      // balanced: launches of the task kernel (each a host round trip)
  int root_lanes = 0;          // balanced: threads per query for kinematics and broad phase
  bool warp_per_pair = false;  // balanced: the small-batch kernel ran (no rounds)
  std::vector<unsigned> round_tasks;  // balanced: tasks per round (the first 32 of each chunk)
  std::size_t finished_tasks = 0;     // balanced: tasks the rounds left to the finish kernel
  std::size_t jobs = 0;               // balanced: body pairs past the broad phase
  unsigned long long bv_tests = 0;
  unsigned long long triangle_tests = 0;
};

class GpuBatchChecker {
 public:
  // Uploads the model once (on every device with kAllDevices). Throws
  // std::runtime_error when no GPU can be used, or not the device asked for (or the
  // library was built without CUDA), saying why.
  GpuBatchChecker(const CollisionModel& model, const GpuCheckerOptions& options);
  ~GpuBatchChecker();
  GpuBatchChecker(const GpuBatchChecker&) = delete;
  GpuBatchChecker& operator=(const GpuBatchChecker&) = delete;

  // configurations: host, shape [n, width]; verdicts: host, shape [n]. Calls from any
  // number of threads are safe and take turns: the device work of one call (its chunk
  // buffers, work queues and counters are the checker's own) runs under a lock, one per
  // device.
  // clearances: host, as CpuBatchChecker::check's.
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
             const float* clearances = nullptr);

  // Of the last check() to finish, whole (a copy: other threads may be checking).
  // With several devices: the parts' chunks, tests and jobs added up, the longest
  // part's milliseconds.
  GpuCheckStats last_stats() const;
  // The device's name; with several, each once with how many ("2 x NVIDIA H100 ...").
  std::string device_name() const;
  // The devices it runs on (one, or every one the process sees), first to last.
  std::vector<int> devices() const;

 private:
  struct Impl;  // the model and buffers on one device
  void release();  // frees each device's buffers with that device current
  std::vector<std::unique_ptr<Impl>> impls_;
  mutable std::mutex stats_mutex_;
  GpuCheckStats last_stats_;  // of the last call to finish, whole
};

}  // namespace gplanner
