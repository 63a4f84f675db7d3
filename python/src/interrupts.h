#pragma once
// Ctrl-C in long calls: the calls run with the GIL released, and poll Python's signal
// handlers now and then (taking the GIL for that moment); a KeyboardInterrupt (or any
// exception a handler raises) stops the work and is raised when the call returns.

#include <chrono>

namespace gplanner::python {

class InterruptPoll {
 public:
  // True once a signal handler raised (its exception is then pending on this thread):
  // asked at most every kPeriod, from a thread that does not hold the GIL.
  bool raised();
  // Throws pybind11::error_already_set where a handler raised; call with the GIL held.
  void rethrow() const;

  static constexpr std::chrono::milliseconds kPeriod{20};

 private:
  bool raised_ = false;
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace gplanner::python
