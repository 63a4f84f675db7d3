#pragma once
// Checkers for OMPL code: gplanner::make_collision_checker, with what OMPL users expect
// of a library's messages: the notice that the gpu backend runs on the CPU (no device,
// or gplanner built without CUDA) goes to OMPL's console (OMPL_WARN), where OMPL's own
// warnings go and an ompl::msg::OutputHandler sees it.

#include <memory>
#include <string>

#include "gplanner/planner/checkers/checker_factory.h"

namespace gplanner::ompl_adapters {

// The checker for `backend` ("gpu", "cpu", "fcl"); throws std::invalid_argument for an
// unknown name. `scene` must outlive the checker; backend() names what runs.
std::unique_ptr<CollisionChecker> make_collision_checker(const Scene& scene,
                                                         const std::string& backend,
                                                         const CheckerOptions& options = {});

}  // namespace gplanner::ompl_adapters
