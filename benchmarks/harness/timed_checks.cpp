#include "harness/timed_checks.h"

#include <chrono>

namespace gplan {
namespace {

thread_local int open_scopes = 0;  // Scopes open on this thread, of any clock

long long now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

CheckClock::Scope::Scope(const CheckClock& clock) : clock_(clock), outermost_(open_scopes++ == 0) {
  if (outermost_) started_ns_ = now_ns();
}

CheckClock::Scope::~Scope() {
  if (outermost_) clock_.nanoseconds_ += now_ns() - started_ns_;
  --open_scopes;
}

bool TimedStateValidityChecker::isValid(const ompl::base::State* state) const {
  const CheckClock::Scope timed(*clock_);
  return StateValidityChecker::isValid(state);
}

bool TimedDiscreteMotionValidator::checkMotion(const ompl::base::State* s1,
                                               const ompl::base::State* s2) const {
  const CheckClock::Scope timed(*clock_);
  return DiscreteMotionValidator::checkMotion(s1, s2);
}

bool TimedDiscreteMotionValidator::checkMotion(
    const ompl::base::State* s1, const ompl::base::State* s2,
    std::pair<ompl::base::State*, double>& lastValid) const {
  const CheckClock::Scope timed(*clock_);
  return DiscreteMotionValidator::checkMotion(s1, s2, lastValid);
}

bool TimedMotionValidator::checkMotion(const ompl::base::State* s1,
                                       const ompl::base::State* s2) const {
  const CheckClock::Scope timed(*clock_);
  return MotionValidator::checkMotion(s1, s2);
}

bool TimedMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                       std::pair<ompl::base::State*, double>& lastValid) const {
  const CheckClock::Scope timed(*clock_);
  return MotionValidator::checkMotion(s1, s2, lastValid);
}

}  // namespace gplan
