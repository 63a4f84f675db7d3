#include "gplanner/planner/planning/certified_motions.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gplanner/planner/scene/scene.h"

namespace gplanner {
namespace {

// A piece of motion `motion` from fraction t0 to t1 along which no robot point moves
// farther than the round's bound.
struct Segment {
  std::size_t motion;
  double t0, t1;
};

}  // namespace

CertifiedMotions::CertifiedMotions(const Scene& scene, CollisionChecker* checker,
                                   const CertifiedMotionOptions& options)
    : scene_(scene), checker_(checker), bound_(scene.robot, scene.space) {
  step_ = options.step > 0 ? options.step : 0.01 * bound_.longest_displacement();
  if (!(step_ > 0)) step_ = 1e-3;  // a robot that cannot move: any bound serves
  finest_step_ = options.finest_step > 0 ? options.finest_step : step_ / 1024;
  self_pairs_ = !scene.robot.checked_pairs().empty();
}

CertifiedMotionStats CertifiedMotions::stats() const {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

bool CertifiedMotions::check_motions(const float* from, const float* to, std::size_t count,
                                     std::uint8_t* invalid) {
  const std::size_t width = scene_.space.width();
  std::fill(invalid, invalid + count, std::uint8_t(0));
  // The first segments: every motion cut so that each moves points at most step_.
  std::vector<Segment> open;
  for (std::size_t m = 0; m < count; ++m) {
    const double length = bound_.displacement(from + m * width, to + m * width);
    const double pieces = std::max(1.0, std::ceil(length / step_));
    if (!std::isfinite(length) || pieces > 1e7) {
      invalid[m] = 1;  // no configuration, or a motion too long to certify
      continue;
    }
    const std::size_t n = static_cast<std::size_t>(pieces);
    for (std::size_t j = 0; j < n; ++j) open.push_back({m, double(j) / n, double(j + 1) / n});
  }
  CertifiedMotionStats stats;
  stats.motions = count;
  std::vector<float> ends;
  std::vector<std::uint8_t> inflated, plain;
  for (double bound = step_; !open.empty(); bound /= 2) {
    if (should_stop_ && should_stop_()) return false;
    ++stats.rounds;
    // Segments of motions found invalid meanwhile are dropped.
    open.erase(std::remove_if(open.begin(), open.end(),
                              [&](const Segment& s) { return invalid[s.motion] != 0; }),
               open.end());
    if (open.empty()) break;
    if (bound < finest_step_) {
      for (const Segment& s : open) invalid[s.motion] = 1;  // not certified: conservative
      break;
    }
    // Both ends of every open segment, with the clearance of this round's bound.
    ends.resize(open.size() * 2 * width);
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Segment& s = open[i];
      scene_.space.interpolate(from + s.motion * width, to + s.motion * width, s.t0,
                               &ends[(2 * i) * width]);
      scene_.space.interpolate(from + s.motion * width, to + s.motion * width, s.t1,
                               &ends[(2 * i + 1) * width]);
    }
    inflated.resize(open.size() * 2);
    checker_->check_inflated(ends.data(), inflated.size(), clearance(bound), inflated.data());
    stats.checks += inflated.size();
    ++stats.batches;
    // Ends that failed: do they collide themselves?
    std::vector<std::size_t> failed;
    for (std::size_t k = 0; k < inflated.size(); ++k)
      if (inflated[k]) failed.push_back(k);
    std::vector<float> failed_ends(failed.size() * width);
    for (std::size_t f = 0; f < failed.size(); ++f)
      std::copy_n(&ends[failed[f] * width], width, &failed_ends[f * width]);
    plain.resize(failed.size());
    if (!failed.empty()) {
      checker_->check(failed_ends.data(), failed.size(), plain.data());
      stats.checks += failed.size();
      ++stats.batches;
    }
    std::vector<std::uint8_t> end_failed(inflated.size(), 0);
    for (std::size_t f = 0; f < failed.size(); ++f) {
      if (plain[f]) invalid[open[failed[f] / 2].motion] = 1;
      end_failed[failed[f]] = 1;
    }
    // Certified segments leave; the others are halved for the next round.
    std::vector<Segment> next;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Segment& s = open[i];
      if (invalid[s.motion] || (!end_failed[2 * i] && !end_failed[2 * i + 1])) continue;
      const double middle = 0.5 * (s.t0 + s.t1);
      next.push_back({s.motion, s.t0, middle});
      next.push_back({s.motion, middle, s.t1});
    }
    open.swap(next);
  }
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_.motions += stats.motions;
  stats_.checks += stats.checks;
  stats_.rounds += stats.rounds;
  stats_.batches += stats.batches;
  return true;
}

}  // namespace gplanner
