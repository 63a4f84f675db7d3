#include "gplanner/planner/checkers/cpu_checker.h"

#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {

CpuChecker::CpuChecker(const Scene& scene, int threads)
    : checker_(build_collision_model(scene), threads) {}

void CpuChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts);
}

void CpuChecker::check_inflated(const float* configurations, std::size_t n, double inflation,
                                std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts, static_cast<float>(inflation));
}

}  // namespace gplanner
