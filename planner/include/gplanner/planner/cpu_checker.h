#pragma once
// The `cpu` backend: the collision core's own code (the same BVHs, leaf tests and
// traversal the GPU runs) on all host threads.

#include <memory>

#include "gplanner/planner/collision_checker.h"
#include "gplanner/planner/scene.h"

namespace gplanner {

class CpuChecker : public CollisionChecker {
 public:
  // threads = 0: all cores. `scene` must outlive the checker.
  explicit CpuChecker(const Scene& scene, int threads = 0);
  ~CpuChecker() override;

  std::string backend() const override { return "cpu"; }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override;

  // BV-pair and triangle tests done by the last check() (all threads together).
  unsigned long long bv_tests() const;
  unsigned long long triangle_tests() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gplanner
