#include "gplanner/planner/checkers/gpu_checker.h"

#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {

GpuChecker::GpuChecker(const Scene& scene, const GpuCheckerOptions& options)
    : traversal_(options.traversal), checker_(build_collision_model(scene), options) {}

void GpuChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts);
}

void GpuChecker::check_clearances(const float* configurations, std::size_t n,
                                  const float* clearances, std::uint8_t* verdicts) {
  checker_.check(configurations, n, verdicts, clearances);
}

}  // namespace gplanner
