#pragma once
// The seeded configurations gplan-bench's workloads are drawn from: uniform states (as
// `gplan check --seed` draws them), and the first uniform states a checker finds free
// (a roadmap's milestones).

#include <cstddef>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace gplan {

// `count` uniform states within the bounds and joint limits, shape [count, width].
std::vector<float> uniform_states(const gplanner::Scene& scene, std::size_t count,
                                  std::uint64_t seed);

// The first `count` uniform states (drawn from `rng`) that `checker` finds free, shape
// [count, width]; empty when `stop` says so. Throws std::runtime_error, naming the scene
// file, `who` and the key `fewer` to lower, when 1,000 draws per state wanted are not
// enough.
std::vector<float> free_states(const gplanner::Scene& scene, gplanner::CollisionChecker* checker,
                               std::size_t count, std::mt19937_64* rng,
                               const std::function<bool()>& stop, const std::string& who,
                               const std::string& fewer);

}  // namespace gplan
