#include "gplanner/planner/ompl/state_validity_checker.h"

#include <ompl/base/SpaceInformation.h>

#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {

StateValidityChecker::StateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           const Scene& scene, CollisionChecker* checker)
    : ompl::base::StateValidityChecker(si), scene_(scene), checker_(checker) {}

bool StateValidityChecker::isValid(const ompl::base::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  std::lock_guard<std::mutex> lock(mutex_);
  rows_.resize(scene_.space.width());
  state_to_row(scene_, state, rows_.data());
  std::uint8_t verdict = 1;
  checker_->check(rows_.data(), 1, &verdict);
  ++checks_;
  return verdict == 0;
}

void StateValidityChecker::areValid(const std::vector<const ompl::base::State*>& states,
                                    std::vector<std::uint8_t>* valid) const {
  const std::size_t n = states.size(), width = scene_.space.width();
  valid->assign(n, 0);
  std::lock_guard<std::mutex> lock(mutex_);
  rows_.resize(n * width);
  std::vector<std::size_t> inside;  // states within bounds, in the batch
  for (std::size_t i = 0; i < n; ++i) {
    if (!si_->satisfiesBounds(states[i])) continue;
    state_to_row(scene_, states[i], &rows_[inside.size() * width]);
    inside.push_back(i);
  }
  verdicts_.assign(inside.size(), 1);
  if (!inside.empty()) checker_->check(rows_.data(), inside.size(), verdicts_.data());
  checks_ += inside.size();
  for (std::size_t k = 0; k < inside.size(); ++k) (*valid)[inside[k]] = verdicts_[k] == 0;
}

}  // namespace gplanner::ompl_adapters
