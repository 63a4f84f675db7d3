#pragma once
// Runs a loop body over [0, n) on host threads, handing out chunks dynamically so that
// uneven work (collision queries vary a lot in cost) keeps every thread busy.

#include <cstddef>
#include <functional>

namespace gplanner {

// Number of threads to use for `requested` (0: all hardware threads).
int resolve_thread_count(int requested);

// Calls body(begin, end, thread) for disjoint chunks covering [0, n); `thread` is in
// [0, threads) and identifies per-thread scratch space. Exceptions from the body are
// rethrown on the caller's thread.
void parallel_for(std::size_t n, int threads,
                  const std::function<void(std::size_t, std::size_t, int)>& body,
                  std::size_t grain = 16);

}  // namespace gplanner
