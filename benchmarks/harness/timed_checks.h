#pragma once
// The time an OMPL planner spends in collision checks, measured by the validity checker
// and motion validators it is given: how much of a plan time any collision checker,
// however fast, could take away (a planner that spends 85% of its time in checks gains
// at most 1 / 0.15 = 6.7x from checks that cost nothing, as many iterations assumed).
// Each timed call costs two reads of the steady clock (tens of nanoseconds, against
// microseconds for the cheapest check), alike for every checker.

#include <ompl/base/DiscreteMotionValidator.h>

#include <atomic>
#include <memory>

#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_validity_checker.h"

namespace gplan {

// Seconds spent in the timed calls, summed over the threads that made them; a call
// inside another timed call (a state check inside a motion check) counts once.
class CheckClock {
 public:
  double seconds() const { return nanoseconds_.load() * 1e-9; }

  // Times the scope it lives in, unless it is inside another Scope of any clock on this
  // thread.
  class Scope {
   public:
    explicit Scope(const CheckClock& clock);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    const CheckClock& clock_;
    bool outermost_;
    long long started_ns_ = 0;
  };

 private:
  mutable std::atomic<long long> nanoseconds_{0};
};

// Our validity checker, its isValid timed.
class TimedStateValidityChecker : public gplanner::ompl_adapters::StateValidityChecker {
 public:
  TimedStateValidityChecker(const ompl::base::SpaceInformationPtr& si, const gplanner::Scene& scene,
                            gplanner::CollisionChecker* checker, std::shared_ptr<CheckClock> clock)
      : StateValidityChecker(si, scene, checker), clock_(std::move(clock)) {}
  bool isValid(const ompl::base::State* state) const override;

 private:
  std::shared_ptr<CheckClock> clock_;
};

// OMPL's DiscreteMotionValidator (the baseline's), its motion checks timed whole: the
// interpolation between samples counts as it does in ours.
class TimedDiscreteMotionValidator : public ompl::base::DiscreteMotionValidator {
 public:
  TimedDiscreteMotionValidator(const ompl::base::SpaceInformationPtr& si,
                               std::shared_ptr<CheckClock> clock)
      : DiscreteMotionValidator(si), clock_(std::move(clock)) {}
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  std::shared_ptr<CheckClock> clock_;
};

// Our motion validator (the plugin's), its motion checks timed.
class TimedMotionValidator : public gplanner::ompl_adapters::MotionValidator {
 public:
  TimedMotionValidator(const ompl::base::SpaceInformationPtr& si, const gplanner::Scene& scene,
                       gplanner::CollisionChecker* checker, gplanner::EdgeChecks edges,
                       std::shared_ptr<CheckClock> clock)
      : MotionValidator(si, scene, checker, edges), clock_(std::move(clock)) {}
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& lastValid) const override;

 private:
  std::shared_ptr<CheckClock> clock_;
};

}  // namespace gplan
