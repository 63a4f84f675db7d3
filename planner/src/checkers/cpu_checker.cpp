#include "gplanner/planner/checkers/cpu_checker.h"

#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {

CpuChecker::CpuChecker(const Scene& scene, int threads)
    : checker_(build_collision_model(scene), threads) {}

void CpuChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts);
}

void CpuChecker::check_clearances(const float* configurations, std::size_t n,
                                  const float* clearances, std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts, clearances);
}

}  // namespace gplanner
