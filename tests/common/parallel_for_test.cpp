// Host thread loops: every index once, thread indices each on one thread at a time,
// calls from many threads at once (and from inside a loop) sharing the helper threads
// instead of each starting its own, helpers kept between calls, and fork().

#include "gplanner/common/parallel_for.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "gplanner/common/scratch_pool.h"
#include "test_support.h"

namespace gplanner {
namespace {

TEST(ParallelFor, EveryIndexOnceAndEachThreadIndexOnOneThread) {
  const std::size_t n = 10000;
  std::vector<std::atomic<int>> seen(n);
  std::vector<std::atomic<int>> running(8);
  std::atomic<int> overlaps{0};
  parallel_for(n, 8, [&](std::size_t begin, std::size_t end, int thread) {
    ASSERT_GE(thread, 0);
    ASSERT_LT(thread, 8);
    if (running[thread]++ != 0) ++overlaps;
    for (std::size_t i = begin; i < end; ++i) ++seen[i];
    --running[thread];
  });
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << i;
  EXPECT_EQ(overlaps, 0);
}

TEST(ParallelFor, AnExceptionReachesTheCaller) {
  EXPECT_THROW(parallel_for(1000, 4,
                            [](std::size_t begin, std::size_t, int) {
                              if (begin >= 500) throw std::runtime_error("body");
                            }),
               std::runtime_error);
}

// Callers on many threads, each loop asking for 4 threads and calling another loop from
// its body: every index of every loop once, and the threads running loop bodies at once
// stay within the callers plus the helpers one process may run.
TEST(ParallelFor, ManyCallersAndNestedLoopsShareTheHelpers) {
  constexpr int kCallers = 8, kOuter = 64, kInner = 64;
  const int limit = kCallers + std::max(resolve_thread_count(0), 4) - 1;
  std::atomic<int> active{0}, peak{0};
  std::vector<std::atomic<int>> seen(kCallers * kOuter * kInner);
  std::vector<std::thread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&, c] {
      parallel_for(
          kOuter, 4,
          [&](std::size_t begin, std::size_t end, int) {
            const int now = ++active;
            for (int p = peak; now > p && !peak.compare_exchange_weak(p, now);) {
            }
            for (std::size_t i = begin; i < end; ++i) {
              parallel_for(
                  kInner, 4,
                  [&](std::size_t b, std::size_t e, int) {
                    for (std::size_t j = b; j < e; ++j) ++seen[(c * kOuter + i) * kInner + j];
                  },
                  8);
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            --active;
          },
          4);
    });
  }
  for (std::thread& caller : callers) caller.join();
  for (std::size_t k = 0; k < seen.size(); ++k) ASSERT_EQ(seen[k], 1) << k;
  EXPECT_LE(peak, limit);
  std::cout << peak << " outer bodies at once at most (" << kCallers << " callers, "
            << resolve_thread_count(0) << " hardware threads)\n";
}

TEST(ScratchPool, EachLeaseHasItsOwnObjectAndObjectsAreReused) {
  std::atomic<int> made{0};
  ScratchPool<int> pool([&] {
    ++made;
    return std::make_unique<int>(0);
  });
  {
    auto a = pool.take();
    auto b = pool.take();
    EXPECT_NE(&*a, &*b);
  }
  EXPECT_EQ(made, 2);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      for (int k = 0; k < 1000; ++k) {
        auto lease = pool.take();
        EXPECT_EQ(++*lease, 1);  // nobody else holds it
        --*lease;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_LE(made, 4 + 2);
}

// Helper threads the system fails to start (here: no address space left for their
// stacks) are not fatal: the threads that did start, at least the calling one, run
// every item, and the budget gets the others back.
TEST(ParallelFor, ThreadsThatFailToStartLeaveTheWholeLoopToThoseThatDid) {
  const std::size_t n = 5000;
  std::vector<std::atomic<int>> seen(n);
  const int code = testing::run_with_address_space_to_spare(std::size_t(24) << 20, [&] {
    parallel_for(
        n, kMaxThreads,
        [&](std::size_t begin, std::size_t end, int) {
          for (std::size_t i = begin; i < end; ++i) seen[i]++;
        },
        1);
    for (const std::atomic<int>& s : seen)
      if (s != 1) return false;
    // Once more: a budget that kept the helpers that never started would be spent.
    std::atomic<std::size_t> second{0};
    parallel_for(
        n, 4, [&](std::size_t begin, std::size_t end, int) { second += end - begin; }, 1);
    return second == n;
  });
  EXPECT_EQ(code, 0) << "0: every item once; 1: items missed or repeated; 2: threw; 134: "
                        "terminated";
}

// Helpers are started once and kept: many calls run on the same few threads, where
// starting threads per call made new ones every time (thread_local flags count each
// thread that ever ran a chunk once).
TEST(ParallelFor, CallsReuseTheSameHelperThreads) {
  static std::atomic<int> threads_seen{0};
  const auto mark = [](std::size_t, std::size_t, int) {
    thread_local bool counted = false;
    if (!counted) {
      counted = true;
      ++threads_seen;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  };
  for (int call = 0; call < 300; ++call) parallel_for(64, 4, mark, 1);
  // This thread and the helpers of the process (started by this test or by earlier ones
  // that asked for more threads): threads started per call would number up to 900.
  EXPECT_LE(threads_seen, 64);
  EXPECT_GE(threads_seen, 1);
}

// fork() leaves the child none of the helper threads (gplan-bench forks its workers):
// the child's loops still run every index once, on helpers of its own.
TEST(ParallelFor, AForkedChildRunsLoopsOnHelpersOfItsOwn) {
  parallel_for(
      1000, 4, [](std::size_t, std::size_t, int) {}, 1);  // helpers exist
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::atomic<std::size_t> sum{0};
    std::atomic<int> top_thread{0};
    parallel_for(
        100000, 4,
        [&](std::size_t begin, std::size_t end, int thread) {
          for (std::size_t i = begin; i < end; ++i) sum += i;
          for (int t = top_thread; thread > t && !top_thread.compare_exchange_weak(t, thread);) {
          }
          std::this_thread::sleep_for(std::chrono::microseconds(20));
        },
        64);
    const bool every_index_once = sum == std::size_t(100000) * 99999 / 2;
    const bool helped = resolve_thread_count(0) == 1 || top_thread > 0;
    _exit(every_index_once ? (helped ? 0 : 2) : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: indices missed or repeated; 2: no helper ran";
}

TEST(ParallelFor, ThreadCountsAreCappedAtTheStatedMaximum) {
  EXPECT_EQ(resolve_thread_count(1 << 30), kMaxThreads);
  EXPECT_EQ(resolve_thread_count(3), 3);
  EXPECT_GE(resolve_thread_count(0), 1);
}

}  // namespace
}  // namespace gplanner
