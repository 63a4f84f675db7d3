#pragma once
// The `gpu` backend: the scene's collision model on the GPU, with a chosen traversal.
// Calls from any number of threads are safe; they take turns on the device (one call's
// device work at a time, under a lock: GpuBatchChecker), so threads add no throughput
// here, only batches do.

#include <memory>

#include "gplanner/collision_gpu/gpu_batch_checker.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

class GpuChecker : public CollisionChecker {
 public:
  // Throws std::runtime_error saying why when no GPU can be used.
  GpuChecker(const Scene& scene, const GpuCheckerOptions& options);

  std::string backend() const override { return "gpu"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override;
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override;
  // Measured on an H100 with the balanced traversal (bench/history/issue4_planning.md): a call of
  // 100 configurations takes 0.4 to 0.7 ms, 10,000 take 0.9 to 2.0 ms.
  std::size_t configurations_per_call_cost() const override { return 8192; }

  // Of the last check() to finish.
  GpuCheckStats last_stats() const { return checker_.last_stats(); }
  std::string device_name() const { return checker_.device_name(); }
  Traversal traversal() const { return traversal_; }

 private:
  Traversal traversal_;
  GpuBatchChecker checker_;
};

}  // namespace gplanner
