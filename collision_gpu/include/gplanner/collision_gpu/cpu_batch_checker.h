#pragma once
// The batch collision checker on host threads: the same core the GPU runs (BVHs, box
// and leaf tests, the split rule, float poses), one query per thread at a time, the
// way the `basic` traversal does on the GPU. Plain C++. Calls from any number of threads
// run in parallel: the model is read-only and a query's scratch lives on its thread's
// stack.

#include <cstddef>
#include <cstdint>
#include <memory>

#include "gplanner/collision_gpu/collision_model.h"

namespace gplanner {

class CpuBatchChecker {
 public:
  // threads = 0: all hardware threads.
  explicit CpuBatchChecker(const CollisionModel& model, int threads = 0);
  ~CpuBatchChecker();
  CpuBatchChecker(const CpuBatchChecker&) = delete;
  CpuBatchChecker& operator=(const CpuBatchChecker&) = delete;

  // configurations: shape [n, width]; verdicts: shape [n] (1: collision). clearances:
  // null, or shape [n, links] (metres): each body checked with its threshold raised by
  // its clearance, as CollisionModelView::clearances says (certified motions,
  // planner/planning/certified_motions.h).
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
             const float* clearances = nullptr);
  // The same on at most `threads` threads (1: the calling thread alone).
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
             const float* clearances, int threads);

  // BV-pair and triangle tests of the last check() to finish (all its threads together),
  // published whole when it ends; with calls from several threads, each of the two reads
  // the call last finished when it is read.
  unsigned long long bv_tests() const;
  unsigned long long triangle_tests() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner
