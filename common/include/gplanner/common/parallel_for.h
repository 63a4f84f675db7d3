#pragma once
// Runs a loop body over [0, n) on host threads, handing out chunks dynamically so that
// uneven work (collision queries vary a lot in cost) keeps every thread busy.

#include <cstddef>
#include <functional>

namespace gplanner {

// Most threads a caller may ask for (gplan's --threads): more would only exhaust the
// system's threads, not add cores.
inline constexpr int kMaxThreads = 1024;

// Number of threads to use for `requested` (0: one per CPU this process may run on, as
// `nproc` counts them under taskset or a cpuset; at most kMaxThreads).
int resolve_thread_count(int requested);

// Calls body(begin, end, thread) for disjoint chunks covering [0, n); `thread` is in
// [0, threads) and no two chunks run at once with the same `thread`. The calling thread
// works too; exceptions from the body are rethrown on it.
//
// The helper threads are started once and kept (a pool shared by the whole process), so
// that a call costs microseconds, not the tens of microseconds a thread's start and join
// take. Calls may come from many threads at once, and from inside a body: the helpers of
// all calls together number at most max(hardware threads, threads) - 1, idle helpers
// join the calls waiting for them, and a call that finds them all busy runs its loop on
// the calling thread alone; no call waits for a helper that is busy elsewhere. A helper
// that the system fails to start is not an error: the threads that did start (at least
// the calling one) run the whole loop. Many callers (an OMPL planner's threads in a
// checker's loop) thus share the cores instead of starting threads by the hundred. A
// child process made by fork() starts a pool of its own.
void parallel_for(std::size_t n, int threads,
                  const std::function<void(std::size_t, std::size_t, int)>& body,
                  std::size_t grain = 16);

}  // namespace gplanner
