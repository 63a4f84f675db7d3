#include "gplanner/common/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace gplanner {
namespace {

// Helper threads running for all parallel_for calls of the process together.
std::atomic<int> g_helpers{0};

// Takes up to `wanted` helpers while the total stays within `limit`; returns how many.
int reserve_helpers(int wanted, int limit) {
  int running = g_helpers.load();
  for (;;) {
    const int take = std::max(0, std::min(wanted, limit - running));
    if (take == 0) return 0;
    if (g_helpers.compare_exchange_weak(running, running + take)) return take;
  }
}

}  // namespace

int resolve_thread_count(int requested) {
  if (requested > 0) return std::min(requested, kMaxThreads);
  // Asked once: it is a query to the system, and small calls ask in every loop.
  static const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return hardware;
}

void parallel_for(std::size_t n, int threads,
                  const std::function<void(std::size_t, std::size_t, int)>& body,
                  std::size_t grain) {
  if (n == 0) return;
  threads = std::max(1, std::min<int>(threads, static_cast<int>((n + grain - 1) / grain)));
  const int helpers =
      threads == 1 ? 0
                   : reserve_helpers(threads - 1, std::max(resolve_thread_count(0), threads) - 1);
  if (helpers == 0) {
    body(0, n, 0);
    return;
  }
  struct Release {
    int count;
    ~Release() { g_helpers -= count; }
  } release{helpers};
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](int thread) {
    try {
      for (;;) {
        const std::size_t begin = next.fetch_add(grain);
        if (begin >= n) break;
        body(begin, std::min(n, begin + grain), thread);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = n;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(helpers);
  try {
    for (int t = 1; t <= helpers; ++t) pool.emplace_back(worker, t);
  } catch (const std::system_error&) {
    // Fewer threads than asked for (the system's limit on threads or memory): those
    // started and the caller do the whole loop, and the others go back to the budget.
    g_helpers -= helpers - static_cast<int>(pool.size());
    release.count = static_cast<int>(pool.size());
  }
  worker(0);
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace gplanner
