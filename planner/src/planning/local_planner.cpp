#include "gplanner/planner/planning/local_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/straight_line.h"

namespace gplanner {

std::vector<int> coarse_to_fine_order(int segments) {
  std::vector<int> order;
  if (segments < 2) return order;
  order.reserve(segments - 1);
  // Breadth-first over intervals [lo, hi]: each interval's midpoint, then its halves.
  std::vector<std::pair<int, int>> level{{0, segments}}, next;
  while (!level.empty()) {
    next.clear();
    for (const auto& [lo, hi] : level) {
      if (hi - lo < 2) continue;
      const int mid = lo + (hi - lo) / 2;
      order.push_back(mid);
      next.emplace_back(lo, mid);
      next.emplace_back(mid, hi);
    }
    level.swap(next);
  }
  return order;
}

LocalPlanner::LocalPlanner(const Scene& scene, CollisionChecker* checker,
                           const LocalPlannerOptions& options)
    : scene_(scene),
      checker_(checker),
      options_(options),
      metric_(make_metric(scene.space, scene.planner)),
      bound_(scene.robot, scene.space),
      // The first batch, before any is timed: 1,024 samples (25 ms of a Panda's on one
      // core), or four times what a call costs where calls cost (the GPU: a Panda's 8,000
      // samples in about half a millisecond), so that a plan's first check is one call,
      // not two.
      batch_size_(options.batch_seconds,
                  std::max<std::size_t>(1024, 4 * checker->configurations_per_call_cost()), 256,
                  options.max_batch_samples) {
  if (!(options.resolution_fraction > 0) && !(options.max_displacement > 0))
    throw std::invalid_argument("local planner: the resolution must be positive");
}

int LocalPlanner::segments(const float* a, const float* b) const {
  const double length = options_.max_displacement > 0
                            ? bound_.displacement(a, b) / options_.max_displacement
                            : component_segments(a, b);
  if (!(length < 1e9)) throw std::invalid_argument("local planner: motion of unbounded length");
  return std::max(1, static_cast<int>(std::ceil(length)));
}

double LocalPlanner::component_segments(const float* a, const float* b) const {
  // As OMPL counts valid segments in a compound space: each component (base position,
  // base rotation, each joint) in steps of the fraction of its own extent, the largest
  // count winning. The rotation's extent is a half turn.
  const ConfigurationSpace& space = scene_.space;
  const double f = options_.resolution_fraction;
  constexpr double kPi = 3.14159265358979323846;
  double count = 0;
  if (space.base == BaseType::kFloating) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    const double extent = (space.base_max - space.base_min).norm();
    if (extent > 0) count = std::sqrt(dx * dx + dy * dy + dz * dz) / (f * extent);
    count = std::max<double>(count, quaternion_angle(a + 3, b + 3) / (f * kPi));
  } else if (space.base == BaseType::kPlanar) {
    const double dx = a[0] - b[0], dy = a[1] - b[1];
    const double extent = (space.base_max - space.base_min).head<2>().norm();
    if (extent > 0) count = std::sqrt(dx * dx + dy * dy) / (f * extent);
    count = std::max<double>(count, angle_difference(a[2], b[2]) / (f * kPi));
  }
  const int offset = space.base_width();
  for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
    const float x = a[offset + j], y = b[offset + j];
    if (space.continuous[j]) {
      count = std::max<double>(count, angle_difference(x, y) / (f * kPi));
    } else if (space.upper[j] > space.lower[j]) {
      count = std::max<double>(count, std::fabs(x - y) / (f * (space.upper[j] - space.lower[j])));
    }
  }
  return count;
}

bool LocalPlanner::check_motions(const float* from, const float* to, std::size_t count,
                                 std::uint8_t* invalid) {
  const std::size_t width = scene_.space.width();
  std::vector<int> segment_count(count);
  for (std::size_t e = 0; e < count; ++e) {
    if (e % 65536 == 0 && e > 0 && should_stop_ && should_stop_()) return false;
    segment_count[e] = segments(from + e * width, to + e * width);
  }
  return check_motions(from, to, count, segment_count.data(), invalid);
}

bool LocalPlanner::check_motions(const float* from, const float* to, std::size_t count,
                                 const int* segment_count, std::uint8_t* invalid) {
  const ConfigurationSpace& space = scene_.space;
  const std::size_t width = space.width();
  add_stats(count, 0, 0);
  // Each motion's samples in coarse-to-fine order, one order shared by every motion of
  // the same segment count (a roadmap's millions of edges have few distinct counts).
  // The stop is looked at every 65,536 motions here too: PRM hands over all its edges.
  std::vector<const std::vector<int>*> order(count);
  std::map<int, std::vector<int>> orders;  // by segment count; nodes never move
  std::size_t remaining = 0;
  for (std::size_t e = 0; e < count; ++e) {
    if (e % 65536 == 0 && e > 0 && should_stop_ && should_stop_()) return false;
    invalid[e] = 0;
    auto it = orders.find(segment_count[e]);
    if (it == orders.end())
      it = orders.emplace(segment_count[e], coarse_to_fine_order(segment_count[e])).first;
    order[e] = &it->second;
    remaining += order[e]->size();
  }
  // next[e]: how many of motion e's samples have been checked.
  std::vector<std::size_t> next(count, 0);
  std::vector<float> samples;
  std::vector<std::uint8_t> verdicts;
  std::size_t per_motion = 1;  // samples per motion this level: 1, 2, 4, ...
  // Where a call costs as much as checking `call_cost` samples and there are more than
  // twice that, a first call of about call_cost samples, the coarsest of every motion,
  // finds most invalid motions (a blocked motion is usually blocked over a stretch) before
  // their other samples are checked: a shortcut round's 256 candidates, mostly invalid,
  // cost two calls of a fraction of the samples instead of one of all. Where all motions
  // are valid, it costs one call more.
  const std::size_t call_cost = checker_->configurations_per_call_cost();
  bool probe = call_cost > 0 && count > 0 && remaining > 2 * call_cost;
  if (probe) per_motion = std::max<std::size_t>(1, call_cost / count);
  // Levels small enough to be answered on the calling thread (a single motion from an
  // OMPL planner, on any backend) cost no more one level at a time than all at once, and
  // a collision found at a coarse level spares the finer ones: as OMPL's
  // DiscreteMotionValidator, which stops at the first colliding sample.
  const std::size_t cheap_calls_up_to = checker_->cheap_calls_up_to();
  std::size_t live = count;  // motions not found invalid, with samples left
  while (remaining > 0) {
    if (call_cost == 0 && options_.least_level_samples > 0 && live > 0)
      per_motion = std::max(per_motion, (options_.least_level_samples + live - 1) / live);
    const bool stepwise = live <= cheap_calls_up_to / per_motion;
    const bool all_at_once = !probe && !stepwise && remaining <= options_.one_batch_samples;
    probe = false;
    std::vector<std::pair<std::uint32_t, int>> picks;  // (motion, sample index)
    for (std::size_t e = 0; e < count; ++e) {
      if (invalid[e]) continue;
      const std::vector<int>& samples_of_e = *order[e];
      const std::size_t take = all_at_once ? samples_of_e.size() - next[e]
                                           : std::min(per_motion, samples_of_e.size() - next[e]);
      for (std::size_t k = 0; k < take; ++k)
        picks.emplace_back(static_cast<std::uint32_t>(e), samples_of_e[next[e] + k]);
      next[e] += take;
    }
    if (picks.empty()) break;
    // Batches of at most max_batch_samples, so that memory stays bounded, and sized to
    // take about batch_seconds, so that the stop is seen often.
    for (std::size_t first = 0, n = 0; first < picks.size(); first += n) {
      if (should_stop_ && should_stop_()) return false;
      n = std::min(batch_size_.next(), picks.size() - first);
      samples.resize(n * width);
      // A motion's picks come together: its line is prepared once per chunk. Chunks of
      // about 64,000 entries (some 0.1 ms), below which waking threads costs more.
      parallel_for(
          n, resolve_thread_count(0),
          [&](std::size_t begin, std::size_t end, int) {
            StraightLine line;
            std::uint32_t line_motion = ~std::uint32_t(0);
            for (std::size_t i = begin; i < end; ++i) {
              const auto [e, j] = picks[first + i];
              if (e != line_motion) {
                line.reset(space, from + e * width, to + e * width);
                line_motion = e;
              }
              line.at(static_cast<double>(j) / segment_count[e], &samples[i * width]);
            }
          },
          std::max<std::size_t>(1024, 65536 / width));
      verdicts.assign(n, 0);
      const auto started = std::chrono::steady_clock::now();
      checker_->check(samples.data(), n, verdicts.data());
      batch_size_.record(
          n, std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
      add_stats(0, n, 1);
      for (std::size_t i = 0; i < n; ++i)
        if (verdicts[i]) invalid[picks[first + i].first] = 1;
    }
    remaining = live = 0;
    for (std::size_t e = 0; e < count; ++e) {
      if (invalid[e] || next[e] == order[e]->size()) continue;
      remaining += order[e]->size() - next[e];
      ++live;
    }
    per_motion *= 2;
  }
  return true;
}

double LocalPlanner::last_valid_fraction(const float* a, const float* b, bool one_call) {
  return last_valid_fraction(a, b, segments(a, b), one_call);
}

double LocalPlanner::last_valid_fraction(const float* a, const float* b, int n, bool one_call) {
  const ConfigurationSpace& space = scene_.space;
  const std::size_t width = space.width();
  n = std::max(1, n);
  // In order from a; where small calls are answered on the calling thread, a few samples
  // a call (1, 2, 4, ...) up to the first collision, else all in one call.
  const std::size_t cheap_calls_up_to = checker_->cheap_calls_up_to();
  std::size_t chunk = cheap_calls_up_to > 0 && !one_call ? 1 : static_cast<std::size_t>(n);
  std::vector<float> samples;
  std::vector<std::uint8_t> verdicts;
  std::size_t batches = 0;
  for (int first = 1; first <= n;) {
    const int last = static_cast<int>(std::min<std::size_t>(n, first - 1 + chunk));
    const std::size_t m = static_cast<std::size_t>(last - first + 1);
    samples.resize(m * width);
    for (int j = first; j <= last; ++j)
      space.interpolate(a, b, static_cast<double>(j) / n, &samples[(j - first) * width]);
    verdicts.assign(m, 0);
    checker_->check(samples.data(), m, verdicts.data());
    ++batches;
    for (int j = first; j <= last; ++j) {
      if (verdicts[j - first]) {
        add_stats(1, static_cast<std::size_t>(last), batches);
        return static_cast<double>(j - 1) / n;
      }
    }
    first = last + 1;
    // Doubling while calls stay cheap; past that, the rest in one call.
    chunk = 2 * chunk <= cheap_calls_up_to ? 2 * chunk : static_cast<std::size_t>(n);
  }
  add_stats(1, n, batches);
  return 1.0;
}

MotionCheckStats LocalPlanner::stats() const {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void LocalPlanner::reset_stats() {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_ = {};
}

void LocalPlanner::add_stats(std::size_t motions, std::size_t samples, std::size_t batches) {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_.motions += motions;
  stats_.samples += samples;
  stats_.batches += batches;
}

}  // namespace gplanner
