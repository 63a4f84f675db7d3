#include "gplanner/planner/planning/milestone_sampler.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/planning/plan_result.h"
#include "gplanner/planner/scene/planner_settings.h"
#include "stage_timer.h"

namespace gplanner {
namespace {

using Clock = std::chrono::steady_clock;

// q turned by a Gaussian rotation vector of standard deviation `sigma` per axis (w x y z
// in and out, q_out = q_in * exp(omega)).
void turn(std::mt19937_64* rng, double sigma, const float* q_in, float* q_out) {
  std::normal_distribution<double> normal(0.0, sigma);
  const Eigen::Vector3d omega(normal(*rng), normal(*rng), normal(*rng));
  const double angle = omega.norm();
  Eigen::Quaterniond q(q_in[0], q_in[1], q_in[2], q_in[3]);
  q.normalize();
  if (angle > 0) q = q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle));
  q_out[0] = static_cast<float>(q.w());
  q_out[1] = static_cast<float>(q.x());
  q_out[2] = static_cast<float>(q.y());
  q_out[3] = static_cast<float>(q.z());
}

double per_weight(double sigma, float weight) { return weight > 0 ? sigma / weight : sigma; }

}  // namespace

SamplerOptions sampler_options(const PlannerSettings& settings) {
  SamplerOptions options;
  options.rotation_spread = settings.sampler.rotation_spread;
  options.bridge_fraction = settings.sampler.bridge_fraction;
  options.bridge_sigma = settings.sampler.bridge_sigma;
  return options;
}

MilestoneSampler::MilestoneSampler(const ConfigurationSpace& space,
                                   const ConfigurationMetric& metric, const SamplerOptions& options)
    : space_(space), metric_(metric), options_(options) {}

void MilestoneSampler::set_endpoints(const float* start, const float* goal) {
  start_.assign(start, start + space_.width());
  goal_.assign(goal, goal + space_.width());
}

void MilestoneSampler::draw(std::mt19937_64* rng, float* q) const {
  space_.sample_uniform(rng, q);
  if (options_.rotation_spread <= 0 || start_.empty() || space_.base == BaseType::kFixed) return;
  // About a rotation on the way from the start's to the goal's.
  const double t = std::uniform_real_distribution<double>(0.0, 1.0)(*rng);
  if (space_.base == BaseType::kFloating) {
    const Eigen::Quaterniond a(start_[3], start_[4], start_[5], start_[6]),
        b(goal_[3], goal_[4], goal_[5], goal_[6]);
    const Eigen::Quaterniond r = a.normalized().slerp(t, b.normalized());
    const float reference[4] = {static_cast<float>(r.w()), static_cast<float>(r.x()),
                                static_cast<float>(r.y()), static_cast<float>(r.z())};
    turn(rng, options_.rotation_spread, reference, q + 3);
  } else {
    std::normal_distribution<double> normal(0.0, options_.rotation_spread);
    q[2] = static_cast<float>(
        wrap_angle(start_[2] + t * wrap_angle(goal_[2] - start_[2]) + normal(*rng)));
  }
}

void MilestoneSampler::perturb(std::mt19937_64* rng, const float* q1, float* q2) const {
  std::normal_distribution<double> normal(0.0, 1.0);
  const double sigma = options_.bridge_sigma;
  std::copy_n(q1, space_.width(), q2);
  const int position_axes = space_.base == BaseType::kFloating ? 3
                            : space_.base == BaseType::kPlanar ? 2
                                                               : 0;
  const double position_sigma = per_weight(sigma, metric_.position_weight);
  for (int k = 0; k < position_axes; ++k) {
    q2[k] = static_cast<float>(
        std::clamp(q1[k] + position_sigma * normal(*rng), space_.base_min[k], space_.base_max[k]));
  }
  const double rotation_sigma = per_weight(sigma, metric_.rotation_weight);
  if (space_.base == BaseType::kFloating) {
    turn(rng, rotation_sigma, q1 + 3, q2 + 3);
  } else if (space_.base == BaseType::kPlanar) {
    q2[2] = static_cast<float>(wrap_angle(q1[2] + rotation_sigma * normal(*rng)));
  }
  const double joint_sigma = per_weight(sigma, metric_.joint_weight);
  const int offset = space_.base_width();
  for (std::size_t i = 0; i < space_.planned_joints.size(); ++i) {
    const double moved = q1[offset + i] + joint_sigma * normal(*rng);
    q2[offset + i] = static_cast<float>(space_.continuous[i]
                                            ? wrap_angle(moved)
                                            : std::clamp(moved, space_.lower[i], space_.upper[i]));
  }
}

bool MilestoneSampler::attempt(std::mt19937_64* rng, std::vector<float>* q) const {
  const int width = space_.width();
  std::bernoulli_distribution is_bridge(options_.bridge_fraction);
  const bool bridge = options_.bridge_fraction > 0 && is_bridge(*rng);
  const std::size_t first = q->size();
  q->resize(first + (bridge ? 2 : 1) * width);
  draw(rng, &(*q)[first]);
  if (bridge) perturb(rng, &(*q)[first], &(*q)[first + width]);
  return bridge;
}

std::size_t MilestoneSampler::sample(std::mt19937_64* rng, std::size_t attempts,
                                     CollisionChecker* checker, std::vector<float>* found,
                                     PlanTimes* times) {
  const int width = space_.width();
  Clock::time_point started = Clock::now();
  // The attempts by stream: the one under way, then new ones, each seeded in turn.
  struct Part {
    std::mt19937_64 rng;
    std::size_t attempts;
    std::size_t first_attempt;
    std::vector<float> q;  // the bridge test's candidates (else written to `plain_q`)
    std::vector<bool> bridge;
  };
  std::vector<Part> parts;
  for (std::size_t left = attempts; left > 0;) {
    if (stream_left_ == 0) {
      stream_.seed((*rng)());
      stream_left_ = kStreamAttempts;
    }
    const std::size_t n = std::min(left, stream_left_);
    parts.push_back({stream_, n, attempts - left, {}, {}});
    stream_left_ -= n;
    left -= n;
  }
  // Without the bridge test every attempt is one candidate, drawn in its place in one
  // buffer (not value-initialised: the parts' threads write all of it, and copying the
  // parts' own candidates together afterwards took as long as drawing them: 181,000 of
  // the piano's on the H200's host, 3 ms each).
  const bool plain = !(options_.bridge_fraction > 0);
  const std::unique_ptr<float[]> plain_q(plain ? new float[attempts * width] : nullptr);
  // A part costs a quarter to half a millisecond (a rigid body's 1,024 attempts), waking
  // the host's threads tens of microseconds: the threads from two parts on.
  parallel_for(
      parts.size(), parts.size() > 1 ? resolve_thread_count(0) : 1,
      [&](std::size_t begin, std::size_t end, int) {
        for (std::size_t p = begin; p < end; ++p) {
          Part& part = parts[p];
          if (plain) {
            for (std::size_t a = 0; a < part.attempts; ++a)
              draw(&part.rng, &plain_q[(part.first_attempt + a) * width]);
            continue;
          }
          part.q.reserve(part.attempts * width * 2);
          part.bridge.resize(part.attempts);
          for (std::size_t a = 0; a < part.attempts; ++a)
            part.bridge[a] = attempt(&part.rng, &part.q);
        }
      },
      1);
  if (stream_left_ > 0) stream_ = parts.back().rng;  // the stream as its last part left it
  // Candidates: one per plain attempt, two per bridge (its ends, q1 then q2).
  std::vector<float> q;
  std::vector<std::size_t> first;  // per attempt: its first candidate row
  std::vector<bool> bridge;
  if (!plain) {
    first.resize(attempts);
    bridge.resize(attempts);
    std::size_t total = 0;
    for (const Part& part : parts) total += part.q.size();
    q.reserve(total);
    std::size_t i = 0;
    for (const Part& part : parts) {
      std::size_t row = q.size() / width;
      for (std::size_t a = 0; a < part.attempts; ++a, ++i) {
        bridge[i] = part.bridge[a];
        first[i] = row;
        row += bridge[i] ? 2 : 1;
      }
      q.insert(q.end(), part.q.begin(), part.q.end());
    }
  }
  const float* candidate = plain ? plain_q.get() : q.data();
  times->sampling += seconds_since(started);
  const std::size_t candidates = plain ? attempts : q.size() / width;
  std::vector<std::uint8_t> verdicts(candidates);
  started = Clock::now();
  checker->check(candidate, candidates, verdicts.data());
  times->state_checks += seconds_since(started);
  if (plain) {
    started = Clock::now();
    for (std::size_t i = 0; i < attempts; ++i)
      if (!verdicts[i]) found->insert(found->end(), &plain_q[i * width], &plain_q[(i + 1) * width]);
    times->sampling += seconds_since(started);
    return candidates;
  }

  // Midpoints of the bridges whose ends both collide, in one more batch.
  started = Clock::now();
  std::vector<float> middles;
  std::vector<std::size_t> middle_of(attempts, attempts);  // per attempt: its midpoint row
  for (std::size_t i = 0; i < attempts; ++i) {
    if (!bridge[i] || !verdicts[first[i]] || !verdicts[first[i] + 1]) continue;
    middle_of[i] = middles.size() / width;
    middles.resize(middles.size() + width);
    const float* ends = &q[first[i] * width];
    space_.interpolate(ends, ends + width, 0.5, &middles[middle_of[i] * width]);
  }
  times->sampling += seconds_since(started);
  std::vector<std::uint8_t> middle_verdicts(middles.size() / width);
  if (!middle_verdicts.empty()) {
    started = Clock::now();
    checker->check(middles.data(), middle_verdicts.size(), middle_verdicts.data());
    times->state_checks += seconds_since(started);
  }

  for (std::size_t i = 0; i < attempts; ++i) {
    const float* milestone = nullptr;
    if (!bridge[i]) {
      if (!verdicts[first[i]]) milestone = &q[first[i] * width];
    } else if (middle_of[i] < attempts && !middle_verdicts[middle_of[i]]) {
      milestone = &middles[middle_of[i] * width];
    }
    if (milestone) found->insert(found->end(), milestone, milestone + width);
  }
  return candidates + middle_verdicts.size();
}

}  // namespace gplanner
