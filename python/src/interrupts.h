#pragma once
// Ctrl-C in long calls: the calls run with the GIL released, and poll Python's signal
// handlers now and then (taking the GIL for that moment); a KeyboardInterrupt (or any
// exception a handler raises) stops the work and is raised when the call returns.

#include <atomic>
#include <chrono>

namespace gplanner::python {

class InterruptPoll {
 public:
  // True once a signal handler raised (its exception is then pending on the thread that
  // asked): asked at most every kPeriod, from threads that do not hold the GIL (the
  // handlers run on the main thread only; elsewhere the answer stays false).
  bool raised();
  // Throws pybind11::error_already_set where a handler raised; call with the GIL held.
  void rethrow() const;

  static constexpr std::chrono::milliseconds kPeriod{20};

 private:
  std::atomic<bool> raised_{false};
  std::atomic<std::chrono::steady_clock::rep> last_{0};  // ticks of the last look
};

}  // namespace gplanner::python
