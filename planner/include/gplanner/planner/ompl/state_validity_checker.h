#pragma once
// An OMPL state validity checker backed by any of our collision backends: a state is
// valid when it lies within the space's bounds and our checker finds it free. Calls
// from several threads are serialised (the backends answer one batch at a time). The
// batch extension answers many states in one call, as the GPU wants them.

#include <ompl/base/StateValidityChecker.h>

#include <cstdint>
#include <mutex>
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
  mutable std::mutex mutex_;
  mutable std::vector<float> rows_;
  mutable std::vector<std::uint8_t> verdicts_;
  mutable std::size_t checks_ = 0;
};

}  // namespace ompl_adapters
}  // namespace gplanner
