#include "gplanner/planner/ompl/state_validity_checker.h"

#include <ompl/base/SpaceInformation.h>

#include <stdexcept>

#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {

StateValidityChecker::StateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                           const Scene& scene, CollisionChecker* checker)
    : ompl::base::StateValidityChecker(si), scene_(scene), checker_(checker) {
  require_scene_state_space(scene, si, "StateValidityChecker");
  if (checker == nullptr)
    throw std::invalid_argument("StateValidityChecker: no collision checker (null)");
}

bool StateValidityChecker::isValid(const ompl::base::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  thread_local std::vector<float> row;  // no allocation per call: calls take microseconds
  row.resize(scene_.space.width());
  state_to_row(scene_, state, row.data());
  std::uint8_t verdict = 1;
  checker_->check(row.data(), 1, &verdict);
  ++checks_;
  return verdict == 0;
}

void StateValidityChecker::areValid(const std::vector<const ompl::base::State*>& states,
                                    std::vector<std::uint8_t>* valid) const {
  const std::size_t n = states.size(), width = scene_.space.width();
  valid->assign(n, 0);
  std::vector<float> rows(n * width);
  std::vector<std::size_t> inside;  // states within bounds, in the batch
  for (std::size_t i = 0; i < n; ++i) {
    if (!si_->satisfiesBounds(states[i])) continue;
    state_to_row(scene_, states[i], &rows[inside.size() * width]);
    inside.push_back(i);
  }
  std::vector<std::uint8_t> verdicts(inside.size(), 1);
  if (!inside.empty()) checker_->check(rows.data(), inside.size(), verdicts.data());
  checks_ += inside.size();
  for (std::size_t k = 0; k < inside.size(); ++k) (*valid)[inside[k]] = verdicts[k] == 0;
}

}  // namespace gplanner::ompl_adapters
