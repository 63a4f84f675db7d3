#include "gplanner/planner/planning/timed_batch_size.h"

#include <algorithm>
#include <cmath>

namespace gplanner {

TimedBatchSize::TimedBatchSize(double target_seconds, std::size_t first, std::size_t least,
                               std::size_t most)
    : target_seconds_(target_seconds),
      least_(std::max<std::size_t>(1, least)),
      most_(std::max(most, least_)),
      size_(target_seconds > 0 ? std::clamp(first, least_, most_) : most_) {}

std::size_t TimedBatchSize::next() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return size_;
}

void TimedBatchSize::record(std::size_t items, double seconds) {
  if (!(target_seconds_ > 0) || items == 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  // Items the target time holds at this call's rate (a call too quick to time: grow).
  const double at_rate =
      seconds > 0 ? items * target_seconds_ / seconds : items * kMaxGrowth;
  double size = std::min(at_rate, static_cast<double>(std::max(items, size_)) * kMaxGrowth);
  // A call smaller than the size asked (the last part of a stage) that kept within the
  // target says nothing against that size: its fixed costs weigh more.
  if (items < size_ && seconds <= target_seconds_) size = std::max(size, static_cast<double>(size_));
  size_ = static_cast<std::size_t>(
      std::clamp(std::floor(size), static_cast<double>(least_), static_cast<double>(most_)));
}

}  // namespace gplanner
