#pragma once
// What a planner's stages cost: their time, and the GPU calls the plan's checker (and
// k-NN, where it has one) made meanwhile; and why a plan must stop. For RoadmapPlanner
// and TreePlanner.

#include <chrono>
#include <cstddef>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/plan_options.h"

namespace gplanner {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Why a plan begun at `started` must stop now: "stopped" (options.should_stop said so),
// "time limit", or null where it may go on.
inline const char* plan_stop_reason(const PlanOptions& options,
                                    std::chrono::steady_clock::time_point started) {
  if (options.should_stop && options.should_stop()) return "stopped";
  if (seconds_since(started) >= options.time_limit_s) return "time limit";
  return nullptr;
}

// The GPU calls `checker` and `neighbors` (may be null) have made so far.
inline std::size_t gpu_calls_of(const CollisionChecker& checker, const NeighborFinder* neighbors) {
  return checker.device_calls() + (neighbors ? neighbors->device_calls() : 0);
}

// Adds the time from construction to destruction to `*sink`, and where `calls` is given
// the GPU calls `checker` and `neighbors` (may be null) made meanwhile to `*calls`.
class StageTimer {
 public:
  explicit StageTimer(double* sink) : sink_(sink), start_(std::chrono::steady_clock::now()) {}
  StageTimer(double* sink, std::size_t* calls, const CollisionChecker& checker,
             const NeighborFinder* neighbors = nullptr)
      : sink_(sink),
        calls_(calls),
        checker_(&checker),
        neighbors_(neighbors),
        calls_before_(gpu_calls_of(checker, neighbors)),
        start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    *sink_ += seconds_since(start_);
    if (calls_) *calls_ += gpu_calls_of(*checker_, neighbors_) - calls_before_;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double* sink_;
  std::size_t* calls_ = nullptr;
  const CollisionChecker* checker_ = nullptr;
  const NeighborFinder* neighbors_ = nullptr;
  std::size_t calls_before_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gplanner
