#include "interrupts.h"

#include <pybind11/pybind11.h>

namespace gplanner::python {

bool InterruptPoll::raised() {
  if (raised_) return true;
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  auto last = last_.load();
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(kPeriod);
  if (now - last < period.count() || !last_.compare_exchange_strong(last, now)) return false;
  pybind11::gil_scoped_acquire gil;
  // Runs the handlers of signals received meanwhile (the main thread only; 0 elsewhere).
  if (PyErr_CheckSignals() != 0) raised_ = true;
  return raised_;
}

void InterruptPoll::rethrow() const {
  if (raised_) throw pybind11::error_already_set();
}

}  // namespace gplanner::python
