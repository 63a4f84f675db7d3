#include "gplanner/collision_gpu/cpu_batch_checker.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "gplanner/collision_gpu/detail/query.h"
#include "gplanner/collision_gpu/model_view.h"
#include "gplanner/common/parallel_for.h"

namespace gplanner {

struct CpuBatchChecker::Impl {
  FlatCollisionModel model;
  CollisionModelView view;
  int threads;
  std::mutex counts_mutex;
  detail::TraversalCounts last_counts;  // of the last call to finish

  Impl(const CollisionModel& m, int requested)
      : model(m), view(model.view()), threads(resolve_thread_count(requested)) {}
};

CpuBatchChecker::CpuBatchChecker(const CollisionModel& model, int threads)
    : impl_(std::make_unique<Impl>(model, threads)) {}

CpuBatchChecker::~CpuBatchChecker() = default;

void CpuBatchChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
                            const float* clearances) {
  check(configurations, n, verdicts, clearances, impl_->threads);
}

void CpuBatchChecker::check(const float* configurations, std::size_t n, std::uint8_t* verdicts,
                            const float* clearances, int threads) {
  Impl& impl = *impl_;
  CollisionModelView view = impl.view;
  view.clearances = clearances;
  // This call's counts (calls from other threads run at once), published when it ends.
  std::atomic<unsigned long long> bv_tests{0}, triangle_tests{0};
  const std::size_t width = view.width;
  threads = std::max(1, std::min(threads, impl.threads));
  // Chunks of one configuration in small calls, so that a call of a few configurations
  // (a motion's level from an OMPL planner, each 3 to 100 us) is spread over the threads
  // too; up to 16 in large calls, where handing out chunks would cost more.
  const std::size_t grain = std::clamp<std::size_t>(n / (4 * std::size_t(threads)), 1, 16);
  parallel_for(n, threads,
               [&](std::size_t begin, std::size_t end, int) {
                 detail::Xf X_WL[detail::kMaxLinks];
                 // Counted on this thread's stack, added to the call's totals once per chunk:
                 // counting in shared totals in every test made the threads wait on each other's
                 // writes.
                 detail::TraversalCounts counts;
                 for (std::size_t i = begin; i < end; ++i) {
                   verdicts[i] = detail::query_collides(view, configurations + i * width,
                                                        query_clearances(view, i), X_WL, &counts)
                                     ? 1
                                     : 0;
                 }
                 bv_tests += counts.bv_tests;
                 triangle_tests += counts.triangle_tests;
               },
               grain);
  const std::lock_guard<std::mutex> lock(impl.counts_mutex);
  impl.last_counts = {bv_tests.load(), triangle_tests.load()};
}

unsigned long long CpuBatchChecker::bv_tests() const {
  const std::lock_guard<std::mutex> lock(impl_->counts_mutex);
  return impl_->last_counts.bv_tests;
}

unsigned long long CpuBatchChecker::triangle_tests() const {
  const std::lock_guard<std::mutex> lock(impl_->counts_mutex);
  return impl_->last_counts.triangle_tests;
}

}  // namespace gplanner
