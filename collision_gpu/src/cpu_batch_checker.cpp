#include "gplanner/collision_gpu/cpu_batch_checker.h"

#include <vector>

#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/collision_gpu/model_view.h"
#include "gplanner/common/parallel_for.h"

namespace gplanner {

struct CpuBatchChecker::Impl {
  FlatCollisionModel model;
  CollisionModelView view;
  int threads;
  std::vector<detail::TraversalCounts> counts;  // per thread

  Impl(const CollisionModel& m, int requested)
      : model(m), view(model.view()), threads(resolve_thread_count(requested)), counts(threads) {}
};

CpuBatchChecker::CpuBatchChecker(const CollisionModel& model, int threads)
    : impl_(std::make_unique<Impl>(model, threads)) {}

CpuBatchChecker::~CpuBatchChecker() = default;

void CpuBatchChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts) {
  Impl& impl = *impl_;
  for (detail::TraversalCounts& c : impl.counts) c = {};
  const std::size_t width = impl.view.width;
  parallel_for(n, impl.threads, [&](std::size_t begin, std::size_t end, int thread) {
    detail::Xf X_WL[detail::kMaxLinks];
    // Counted on this thread's stack, added to its total once per chunk: the totals of
    // several threads share a cache line, and counting there in every test made the
    // threads wait on each other's writes.
    detail::TraversalCounts counts;
    for (std::size_t i = begin; i < end; ++i) {
      verdicts[i] =
          detail::query_collides(impl.view, configurations + i * width, X_WL, &counts) ? 1 : 0;
    }
    impl.counts[thread].bv_tests += counts.bv_tests;
    impl.counts[thread].triangle_tests += counts.triangle_tests;
  });
}

unsigned long long CpuBatchChecker::bv_tests() const {
  unsigned long long total = 0;
  for (const detail::TraversalCounts& c : impl_->counts) total += c.bv_tests;
  return total;
}

unsigned long long CpuBatchChecker::triangle_tests() const {
  unsigned long long total = 0;
  for (const detail::TraversalCounts& c : impl_->counts) total += c.triangle_tests;
  return total;
}

}  // namespace gplanner
