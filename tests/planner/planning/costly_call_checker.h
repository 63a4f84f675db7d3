#pragma once
// The cpu backend, saying that a call costs as much as `per_call` configurations (as the
// GPU's calls do): for tests of the planner code that batches differently on such a
// checker. It counts its calls and the configurations they held (calls from several
// threads at once too).

#include <atomic>
#include <string>

#include "gplanner/planner/checkers/cpu_checker.h"

namespace gplanner::testing {

class CostlyCallChecker : public CollisionChecker {
 public:
  CostlyCallChecker(const Scene& scene, std::size_t per_call) : cpu_(scene), per_call_(per_call) {}
  std::string backend() const override { return cpu_.backend(); }
  void check(const float* configurations, std::size_t n, std::uint8_t* verdicts) override {
    cpu_.check(configurations, n, verdicts);
    ++calls_;
    checked_ += n;
  }
  void check_clearances(const float* configurations, std::size_t n, const float* clearances,
                        std::uint8_t* verdicts) override {
    cpu_.check_clearances(configurations, n, clearances, verdicts);
    ++calls_;
    checked_ += n;
  }
  std::size_t configurations_per_call_cost() const override { return per_call_; }
  // No call is free of its fixed cost (as a GPU call): motions are not checked a level a
  // call for the sake of stopping early.
  std::size_t cheap_calls_up_to() const override { return 0; }
  // Every call stands for a GPU call.
  std::size_t device_calls() const override { return calls_; }
  std::size_t checked() const { return checked_; }

 private:
  CpuChecker cpu_;
  std::size_t per_call_;
  std::atomic<std::size_t> calls_{0}, checked_{0};
};

}  // namespace gplanner::testing
