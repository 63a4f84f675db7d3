#include "interrupts.h"

#include <pybind11/pybind11.h>

namespace gplanner::python {

bool InterruptPoll::raised() {
  if (raised_) return true;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < kPeriod) return false;
  last_ = now;
  pybind11::gil_scoped_acquire gil;
  // Runs the handlers of signals received meanwhile (the main thread only; 0 elsewhere).
  raised_ = PyErr_CheckSignals() != 0;
  return raised_;
}

void InterruptPoll::rethrow() const {
  if (raised_) throw pybind11::error_already_set();
}

}  // namespace gplanner::python
