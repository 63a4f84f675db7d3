#include "gplanner/planner/planning/certified_motions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"

namespace gplanner {
namespace {

// A piece of motion `motion` from fraction t0 to t1, and whether each end is known to
// keep the clearance this round asks (it kept a larger one in an earlier round).
struct Segment {
  std::size_t motion;
  double t0, t1;
  bool good0, good1;
};

// c rounded up to a float (clearances are bounds: never rounded down).
float float_at_least(double c) {
  const float f = static_cast<float>(c);
  return double(f) >= c ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

}  // namespace

CertifiedMotions::CertifiedMotions(const Scene& scene, CollisionChecker* checker,
                                   const CertifiedMotionOptions& options)
    : scene_(scene),
      checker_(checker),
      bound_(scene.robot, scene.space),
      // The first batch of ends, before any is timed: 256, or twice what a call costs
      // where calls cost (half the local planner's: an end may need a plain check
      // besides its clearances).
      batch_size_(options.batch_seconds,
                  std::max<std::size_t>(256, 2 * checker->configurations_per_call_cost()), 64,
                  std::max<std::size_t>(options.max_batch, 64)) {
  step_ = options.step;
  if (!(step_ > 0)) {
    // Larger steps make fewer segments but larger clearances, and the cost of a check
    // grows fast with its clearance; near obstacles, out of all proportion (measured:
    // benchmarks/history/tuning_notes.md, "Certified motions' step").
    step_ = 0.01 * bound_.longest_displacement();
    const double robot_size = tolerance_band(scene).robot_size;
    if (robot_size > 0) step_ = std::min(step_, 0.01 * robot_size);
  }
  if (!(step_ > 0)) step_ = 1e-3;  // a robot that cannot move: any bound serves
  finest_step_ = options.finest_step > 0 ? options.finest_step : step_ / 1024;
}

CertifiedMotionStats CertifiedMotions::stats() const {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

void CertifiedMotions::reset_stats() {
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_ = {};
}

bool CertifiedMotions::check_motions(const float* from, const float* to, std::size_t count,
                                     std::uint8_t* invalid) {
  const std::size_t width = scene_.space.width();
  const std::size_t links = scene_.robot.links.size();
  std::fill(invalid, invalid + count, std::uint8_t(0));
  // Per motion: each link's displacement bound over the whole motion, and the number of
  // first segments, so that no link moves farther than step_ along one.
  std::vector<double> motion_bounds(count * links);
  std::vector<Segment> open;
  for (std::size_t m = 0; m < count; ++m) {
    double* bounds = &motion_bounds[m * links];
    bound_.link_displacements(from + m * width, to + m * width, bounds);
    double longest = 0;
    bool finite = true;
    for (std::size_t l = 0; l < links; ++l) {
      finite = finite && std::isfinite(bounds[l]);
      longest = std::max(longest, bounds[l]);
    }
    const double pieces = std::max(1.0, std::ceil(longest / step_));
    if (!finite || pieces > 1e7) {
      invalid[m] = 1;  // no configuration, or a motion too long to certify
      continue;
    }
    const std::size_t n = static_cast<std::size_t>(pieces);
    for (std::size_t j = 0; j < n; ++j)
      open.push_back({m, double(j) / n, double(j + 1) / n, false, false});
  }
  CertifiedMotionStats stats;
  stats.motions = count;
  // Where a call has a fixed cost (the GPU's: on the MotionBenchMaker Panda a call of a
  // few dozen ends costs as much as one of 2,000 more), a round is one call where its
  // ends number fewer than that: its ends checked with their clearances and, in the same
  // call, without (whether an end that fails its clearance collides itself); and
  // segments that fail are cut into quarters rather than halves, reaching a given length
  // in half the rounds. On the CPU backends, where a check costs its work alone, the
  // plain checks are of the ends that failed only, and segments are halved.
  const std::size_t call_cost = checker_->configurations_per_call_cost();
  const int cuts = call_cost > 0 ? 4 : 2;
  std::vector<float> ends, clearances;
  std::vector<std::uint8_t> verdicts, plain;
  // Checks n configurations without clearances in a call of their own, into `plain`.
  const auto check_plain = [&](const float* q, std::size_t n) {
    plain.resize(n);
    checker_->check(q, n, plain.data());
    stats.checks += n;
    ++stats.batches;
  };
  // Where calls cost and a round's ends outnumber a call's cost, the plain checks of the
  // ends that failed go into the next round's call rather than a call of their own (on
  // MotionBenchMaker's Panda, a path's first round of 2,000 to 3,000 ends, a few dozen
  // failing: a call of 0.1 to 0.14 ms saved). Their segments are cut meanwhile; an end
  // that collides fails every clearance, so its motion keeps open segments, and is made
  // invalid, when its plain verdict comes. Each deferred end: its configuration, motion.
  std::vector<float> deferred;
  std::vector<std::size_t> deferred_motion;
  // The deferred ends' plain verdicts (`collides`, in their order) taken: a colliding
  // end's motion is invalid; none is deferred after.
  const auto take_deferred_verdicts = [&](const std::uint8_t* collides) {
    for (std::size_t d = 0; d < deferred_motion.size(); ++d)
      if (collides[d]) invalid[deferred_motion[d]] = 1;
    deferred.clear();
    deferred_motion.clear();
  };
  const auto drop_deferred_of_invalid = [&] {  // their motions' verdicts are in
    std::size_t kept = 0;
    for (std::size_t d = 0; d < deferred_motion.size(); ++d) {
      if (invalid[deferred_motion[d]]) continue;
      std::copy_n(&deferred[d * width], width, &deferred[kept * width]);
      deferred_motion[kept++] = deferred_motion[d];
    }
    deferred.resize(kept * width);
    deferred_motion.resize(kept);
  };
  while (!open.empty()) {
    if (should_stop_ && should_stop_()) return false;
    ++stats.rounds;
    // Segments of motions found invalid meanwhile are dropped.
    open.erase(std::remove_if(open.begin(), open.end(),
                              [&](const Segment& s) { return invalid[s.motion] != 0; }),
               open.end());
    drop_deferred_of_invalid();
    if (open.empty()) break;
    // The ends to check: those not known good, each once. Within a round all open
    // segments of one motion have the same length (each round halves them), so two that
    // meet ask the same clearances at the end they share: half of each link's bound over
    // the segment (a configuration inside lies within half a segment of an end).
    ends.clear();
    clearances.clear();
    ends.reserve(4 * open.size() * width);  // room for the plain checks' copy too
    clearances.reserve(4 * open.size() * links);
    std::vector<std::size_t> end_index(open.size() * 2, SIZE_MAX);
    std::vector<std::size_t> end_motion;  // each end's motion
    end_motion.reserve(2 * open.size());
    // Each link's clearance (a float) for the segments of one motion, of one length: made
    // again where a segment is longer than the row's own (t1 - t0 differs in its last
    // bits between segments of one length) or more than a billionth shorter, so that no
    // end asks less than its segment needs.
    std::vector<float> row(links);
    std::size_t row_motion = SIZE_MAX;
    double row_fraction = -1;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Segment& s = open[i];
      const double fraction = s.t1 - s.t0;
      if (s.motion != row_motion || fraction > row_fraction ||
          fraction < row_fraction * (1 - 1e-9)) {
        const double* bounds = &motion_bounds[s.motion * links];
        for (std::size_t l = 0; l < links; ++l) row[l] = float_at_least(0.5 * bounds[l] * fraction);
        row_motion = s.motion;
        row_fraction = fraction;
      }
      const auto add_end = [&](double t) {
        const std::size_t e = ends.size() / width;
        end_motion.push_back(s.motion);
        ends.resize(ends.size() + width);
        scene_.space.interpolate(from + s.motion * width, to + s.motion * width, t,
                                 &ends[e * width]);
        clearances.insert(clearances.end(), row.begin(), row.end());
        return e;
      };
      const bool shares = i > 0 && open[i - 1].motion == s.motion && open[i - 1].t1 == s.t0;
      if (!s.good0)
        end_index[2 * i] =
            shares && end_index[2 * i - 1] != SIZE_MAX ? end_index[2 * i - 1] : add_end(s.t0);
      if (!s.good1) end_index[2 * i + 1] = add_end(s.t1);
    }
    const std::size_t n_ends = ends.size() / width;
    // One call where the plain checks add fewer rows than a call costs.
    const bool one_call = call_cost > 0 && n_ends <= call_cost;
    if (one_call) {  // the same ends again, with no clearance
      ends.resize(2 * ends.size());  // (insert() may not copy a vector's own elements)
      std::copy_n(ends.begin(), ends.size() / 2, ends.begin() + ends.size() / 2);
      clearances.resize(2 * clearances.size(), 0.0f);
    }
    // The last round's deferred ends, plain, last.
    const std::size_t deferred_first = ends.size() / width, deferred_count = deferred_motion.size();
    ends.insert(ends.end(), deferred.begin(), deferred.end());
    clearances.resize(clearances.size() + deferred_count * links, 0.0f);
    const std::size_t rows = ends.size() / width;
    verdicts.resize(rows);
    for (std::size_t first = 0, n = 0; first < rows; first += n) {
      if (first > 0 && should_stop_ && should_stop_()) return false;
      n = one_call ? rows : std::min(batch_size_.next(), rows - first);
      const auto start = std::chrono::steady_clock::now();
      checker_->check_clearances(&ends[first * width], n, &clearances[first * links],
                                 &verdicts[first]);
      batch_size_.record(
          n, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      stats.checks += n;
      ++stats.batches;
    }
    take_deferred_verdicts(verdicts.data() + deferred_first);  // none deferred: the end
    // Ends that failed: do they collide themselves?
    std::vector<std::size_t> failed;
    for (std::size_t e = 0; e < n_ends; ++e)
      if (verdicts[e]) failed.push_back(e);
    if (one_call) {
      for (const std::size_t e : failed) verdicts[e] = verdicts[n_ends + e] ? 2 : 1;
    } else if (call_cost > 0) {  // in the next round's call; free but closer till then
      for (const std::size_t e : failed) {
        verdicts[e] = 1;
        deferred.insert(deferred.end(), &ends[e * width], &ends[(e + 1) * width]);
        deferred_motion.push_back(end_motion[e]);
      }
    } else if (!failed.empty()) {
      std::vector<float> failed_ends(failed.size() * width);
      for (std::size_t f = 0; f < failed.size(); ++f)
        std::copy_n(&ends[failed[f] * width], width, &failed_ends[f * width]);
      check_plain(failed_ends.data(), failed.size());
      for (std::size_t f = 0; f < failed.size(); ++f) verdicts[failed[f]] = plain[f] ? 2 : 1;
    }
    // 0: kept the clearance; 1: free but closer; 2: colliding. Certified segments leave;
    // the others are cut (into `cuts` pieces) for the next round, the ends that kept
    // their clearance known good.
    std::vector<Segment> next;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const Segment& s = open[i];
      if (invalid[s.motion]) continue;
      const std::uint8_t v0 = s.good0 ? 0 : verdicts[end_index[2 * i]];
      const std::uint8_t v1 = s.good1 ? 0 : verdicts[end_index[2 * i + 1]];
      if (v0 == 2 || v1 == 2) {
        invalid[s.motion] = 1;
        continue;
      }
      if (v0 == 0 && v1 == 0) continue;
      const double* bounds = &motion_bounds[s.motion * links];
      if (*std::max_element(bounds, bounds + links) * 0.5 * (s.t1 - s.t0) < finest_step_) {
        invalid[s.motion] = 1;  // not certified at the finest step: conservative
        continue;
      }
      for (int c = 0; c < cuts; ++c) {
        const double a = c == 0 ? s.t0 : s.t0 + (s.t1 - s.t0) * c / cuts;
        const double b = c + 1 == cuts ? s.t1 : s.t0 + (s.t1 - s.t0) * (c + 1) / cuts;
        next.push_back({s.motion, a, b, c == 0 && v0 == 0, c + 1 == cuts && v1 == 0});
      }
    }
    open.swap(next);
  }
  // Ends still deferred once no segment is open: checked now (an end that collides keeps
  // its motion's segments open, so none should be left; should one be, it still counts).
  drop_deferred_of_invalid();
  if (!deferred_motion.empty()) {
    check_plain(deferred.data(), deferred_motion.size());
    take_deferred_verdicts(plain.data());
  }
  const std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_.motions += stats.motions;
  stats_.checks += stats.checks;
  stats_.rounds += stats.rounds;
  stats_.batches += stats.batches;
  return true;
}

}  // namespace gplanner
