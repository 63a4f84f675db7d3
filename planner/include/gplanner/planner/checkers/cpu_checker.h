#pragma once
// The `cpu` backend: the scene's collision model checked by the collision core's own
// code (the same BVHs, leaf tests and traversal the GPU runs) on host threads.

#include "gplanner/collision_gpu/cpu_batch_checker.h"
#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

class CpuChecker : public CollisionChecker {
 public:
  // threads = 0: all cores.
  explicit CpuChecker(const Scene& scene, int threads = 0);

  std::string backend() const override { return "cpu"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override;
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override;

  // BV-pair and triangle tests done by the last check() (all threads together).
  unsigned long long bv_tests() const { return checker_.bv_tests(); }
  unsigned long long triangle_tests() const { return checker_.triangle_tests(); }

 private:
  CpuBatchChecker checker_;
};

}  // namespace gplanner
