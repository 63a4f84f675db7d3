#include "gplanner/common/parallel_for.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace gplanner {
namespace {

// One parallel_for call's loop, shared by its caller and the helpers that join it.
struct Loop {
  const std::function<void(std::size_t, std::size_t, int)>* body = nullptr;
  std::size_t n = 0, grain = 1;
  std::atomic<std::size_t> next{0};
  std::mutex mutex;  // guards the fields below
  std::condition_variable left;
  int limit = 0;        // most helpers busy in the whole process while one joins
  int seats = 0;        // helpers that may still join
  int joined = 0;       // helpers that joined (their thread indices are 1 .. joined)
  int running = 0;      // helpers in the loop now
  bool closed = false;  // the caller is done: nobody joins any more
  std::exception_ptr error;

  // Takes chunks until none is left; thread: this runner's index.
  void run(int thread) {
    try {
      for (;;) {
        const std::size_t begin = next.fetch_add(grain);
        if (begin >= n) break;
        (*body)(begin, std::min(n, begin + grain), thread);
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex);
      if (!error) error = std::current_exception();
      next = n;
    }
  }
};

// Helper threads started once and kept for the whole process: a call no longer pays
// for starting and joining threads (tens of microseconds each, which small batches from
// OMPL's planners paid on every call). Loops wait in a queue; an idle helper joins the
// first one with a seat left. A helper that joins a loop its caller has already
// finished leaves at once, so that no call ever waits for a helper that was busy.
class HelperPool {
 public:
  // Offers `seats` seats of `loop` to the helpers while at most `limit` helpers are busy
  // in all, starting more helpers (up to `limit` in all) where too few are idle.
  void offer(const std::shared_ptr<Loop>& loop, int seats, int limit) {
    std::unique_lock<std::mutex> lock(mutex_);
    seats = std::min(seats, limit - (started_ - idle_));  // helpers busy elsewhere count
    if (seats <= 0) return;
    loop->limit = limit;
    int to_start = std::max(0, std::min(seats - idle_, limit - started_));
    for (; to_start > 0; --to_start) {
      try {
        std::thread(&HelperPool::serve, this).detach();
        ++started_;
        ++idle_;
      } catch (const std::system_error&) {
        break;  // the system's limit on threads or memory: those running do the work
      }
    }
    loop->seats = std::min(seats, idle_);
    if (loop->seats == 0) return;
    queue_.push_back(loop);
    for (int s = 0; s < loop->seats; ++s) wake_.notify_one();
  }

  // Takes back the seats of `loop` that no helper took.
  void withdraw(const std::shared_ptr<Loop>& loop) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = std::find(queue_.begin(), queue_.end(), loop);
    if (it != queue_.end()) queue_.erase(it);
  }

  // After fork(): the child has none of the helper threads; start afresh (the old
  // pool's lock may have been held by a thread that does not exist there).
  static void reset_after_fork() { slot() = new HelperPool; }
  static void lock_for_fork() { instance().mutex_.lock(); }
  static void unlock_after_fork() { instance().mutex_.unlock(); }

  static HelperPool& instance() {
    static const bool registered = [] {
      pthread_atfork(&HelperPool::lock_for_fork, &HelperPool::unlock_after_fork,
                     &HelperPool::reset_after_fork);
      return true;
    }();
    (void)registered;
    return *slot();
  }

 private:
  void serve() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return !queue_.empty(); });
      const std::shared_ptr<Loop> loop = queue_.front();
      if (--loop->seats <= 0) queue_.pop_front();
      if (started_ - idle_ >= loop->limit) continue;  // enough helpers busy: leave the seat
      --idle_;
      lock.unlock();
      int thread = 0;
      {
        const std::lock_guard<std::mutex> loop_lock(loop->mutex);
        if (!loop->closed) {
          thread = ++loop->joined;
          ++loop->running;
        }
      }
      if (thread > 0) {
        loop->run(thread);
        const std::lock_guard<std::mutex> loop_lock(loop->mutex);
        if (--loop->running == 0) loop->left.notify_all();
      }
      lock.lock();
      ++idle_;
    }
  }

  // Leaked on purpose: helpers wait on it until the process ends, and a destructor run
  // at exit would have to stop threads that other static destructors may still use.
  static HelperPool*& slot() {
    static HelperPool* pool = new HelperPool;
    return pool;
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::shared_ptr<Loop>> queue_;  // loops with seats left
  int started_ = 0, idle_ = 0;
};

}  // namespace

int resolve_thread_count(int requested) {
  if (requested > 0) return std::min(requested, kMaxThreads);
  // Asked once: it is a query to the system, and small calls ask in every loop. The CPUs
  // this process may run on (taskset, a container's or a batch job's cpuset), as
  // nproc counts them; the machine's count where the mask cannot be read.
  static const int hardware = [] {
    cpu_set_t mask;
    CPU_ZERO(&mask);
    if (sched_getaffinity(0, sizeof(mask), &mask) == 0 && CPU_COUNT(&mask) > 0)
      return CPU_COUNT(&mask);
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }();
  return hardware;
}

void parallel_for(std::size_t n, int threads,
                  const std::function<void(std::size_t, std::size_t, int)>& body,
                  std::size_t grain) {
  if (n == 0) return;
  grain = std::max<std::size_t>(1, grain);
  threads = std::max(1, std::min<int>(threads, static_cast<int>((n + grain - 1) / grain)));
  if (threads == 1) {
    body(0, n, 0);
    return;
  }
  const auto loop = std::make_shared<Loop>();
  loop->body = &body;
  loop->n = n;
  loop->grain = grain;
  HelperPool& pool = HelperPool::instance();
  pool.offer(loop, threads - 1, std::max(resolve_thread_count(0), threads) - 1);
  loop->run(0);
  // Seats nobody took are withdrawn; helpers still in the loop are waited for.
  pool.withdraw(loop);
  std::unique_lock<std::mutex> lock(loop->mutex);
  loop->closed = true;
  loop->left.wait(lock, [&] { return loop->running == 0; });
  if (loop->error) std::rethrow_exception(loop->error);
}

}  // namespace gplanner
