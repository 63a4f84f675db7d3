#pragma once
// An OMPL state validity checker backed by any of our collision backends: a state is
// valid when it lies within the space's bounds and our checker finds it free. Calls
// from any number of threads run at once, each with its own buffers (every backend
// takes concurrent calls; see collision_checker.h for which run in parallel). The batch
// extension answers many states in one call, as the GPU wants them.

#include <ompl/base/StateValidityChecker.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"

namespace gplanner {

struct Scene;

namespace ompl_adapters {

class StateValidityChecker : public ompl::base::StateValidityChecker {
 public:
  // scene and checker must outlive this object.
  StateValidityChecker(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                       CollisionChecker* checker);

  bool isValid(const ompl::base::State* state) const override;

  // valid[i] = 1 when states[i] is valid; all states checked in one batch.
  void areValid(const std::vector<const ompl::base::State*>& states,
                std::vector<std::uint8_t>* valid) const;

  // States checked so far (single and batched calls).
  std::size_t checks() const { return checks_; }

 private:
  const Scene& scene_;
  CollisionChecker* checker_;
  mutable std::atomic<std::size_t> checks_{0};
};

}  // namespace ompl_adapters
}  // namespace gplanner
