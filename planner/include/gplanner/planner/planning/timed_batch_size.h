#pragma once
// Batch sizes from measured throughput, so that one call of a long stage (a checker
// call on sampled milestones or edge samples, a k-NN call) takes about a target time:
// the planner sees a stop or its time limit between calls, however slow the backend or
// large the input, while fast backends still get large batches.

#include <cstddef>
#include <mutex>

namespace gplanner {

class TimedBatchSize {
 public:
  // target_seconds: how long one call should take (0: no target, every batch `most`);
  // first: the size before any call is measured; least, most: bounds on every size.
  TimedBatchSize(double target_seconds, std::size_t first, std::size_t least, std::size_t most);

  // The next batch's size: the target time at the last measured rate, growing at most
  // kMaxGrowth-fold a call (a fast small batch may not speak for a large one), within
  // [least, most]. Callers on several threads may ask and record at once.
  std::size_t next() const;
  // A call of `items` took `seconds`.
  void record(std::size_t items, double seconds);

  static constexpr double kMaxGrowth = 8;

 private:
  mutable std::mutex mutex_;
  double target_seconds_;
  std::size_t least_, most_;
  std::size_t size_;  // the next size
};

}  // namespace gplanner
