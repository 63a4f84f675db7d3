#include "gplanner/planner/cpu_checker.h"

#include <vector>

#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/planner/parallel_for.h"
#include "gplanner/planner/scene_collision_model.h"

namespace gplanner {

struct CpuChecker::Impl {
  FlatCollisionModel model;
  CollisionModelView view;
  int threads;
  std::vector<detail::TraversalCounts> counts;  // per thread

  Impl(const Scene& scene, int requested)
      : model(build_collision_model(scene)),
        view(model.view()),
        threads(resolve_thread_count(requested)),
        counts(threads) {}
};

CpuChecker::CpuChecker(const Scene& scene, int threads)
    : impl_(std::make_unique<Impl>(scene, threads)) {}

CpuChecker::~CpuChecker() = default;

void CpuChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  Impl& impl = *impl_;
  for (detail::TraversalCounts& c : impl.counts) c = {};
  const std::size_t width = impl.view.width;
  parallel_for(n, impl.threads, [&](std::size_t begin, std::size_t end, int thread) {
    detail::Xf X_WL[detail::kMaxLinks];
    for (std::size_t i = begin; i < end; ++i) {
      verdicts[i] =
          detail::query_collides(impl.view, configurations + i * width, X_WL, &impl.counts[thread])
              ? 1
              : 0;
    }
  });
}

unsigned long long CpuChecker::bv_tests() const {
  unsigned long long total = 0;
  for (const detail::TraversalCounts& c : impl_->counts) total += c.bv_tests;
  return total;
}

unsigned long long CpuChecker::triangle_tests() const {
  unsigned long long total = 0;
  for (const detail::TraversalCounts& c : impl_->counts) total += c.triangle_tests;
  return total;
}

}  // namespace gplanner
