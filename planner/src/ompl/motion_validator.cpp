#include "gplanner/planner/ompl/motion_validator.h"

#include <stdexcept>

#include <ompl/base/SpaceInformation.h>

#include <algorithm>
#include <chrono>

#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {

namespace {

// The checker a motion validator is made with, checked first (its members use it).
CollisionChecker* required(CollisionChecker* checker) {
  if (checker == nullptr)
    throw std::invalid_argument("MotionValidator: no collision checker (null)");
  return checker;
}

}  // namespace

MotionValidator::MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                                 CollisionChecker* checker)
    : MotionValidator(si, scene, checker, EdgeChecks::kCertified) {}

MotionValidator::MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                                 CollisionChecker* checker, const LocalPlannerOptions& options)
    : ompl::base::MotionValidator(si),
      scene_(scene),
      checker_(required(checker)),
      local_(scene, checker, options),
      host_local_(scene, checker->host_checker(), options),
      follows_space_resolution_(false),
      certifier_(scene, checker) {
  require_scene_state_space(scene, si, "MotionValidator");
}

MotionValidator::MotionValidator(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                                 CollisionChecker* checker, EdgeChecks edges,
                                 const CertifiedMotionOptions& certified)
    : ompl::base::MotionValidator(si),
      scene_(scene),
      checker_(required(checker)),
      local_(scene, checker, plan_options(scene).local),
      host_local_(scene, checker->host_checker(), plan_options(scene).local),
      edges_(edges),
      follows_space_resolution_(!(plan_options(scene).local.max_displacement > 0)),
      certifier_(scene, checker, certified) {
  require_scene_state_space(scene, si, "MotionValidator");
}

int MotionValidator::segments(const ompl::base::State* s1, const ompl::base::State* s2,
                              const float* a, const float* b) const {
  // Before setup() the space has no segment length yet (OMPL's count would divide by 0).
  if (!follows_space_resolution_ || !si_->isSetup()) return local_.segments(a, b);
  // At most ten times the segments a scene may ask for (memory: a motion's samples may
  // go in one batch).
  const double most = 10 * kMaxEdgeSegments;
  return static_cast<int>(
      std::clamp<double>(si_->getStateSpace()->validSegmentCount(s1, s2), 1, most));
}

bool MotionValidator::certified_free(const float* a, const float* b) const {
  std::uint8_t invalid = 1;
  certifier_.check_motions(a, b, 1, &invalid);
  return invalid == 0;
}

bool MotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const {
  // As OMPL's DiscreteMotionValidator: the end state first, then the samples between,
  // coarse to fine, up to the first collision (on the host where the checker answers
  // small calls there).
  if (!si_->satisfiesBounds(s2)) {
    count(0, 1);
    return false;
  }
  const int width = scene_.space.width();
  thread_local std::vector<float> a, b;
  a.resize(width);
  b.resize(width);
  state_to_row(scene_, s1, a.data());
  state_to_row(scene_, s2, b.data());
  const bool valid = edges_ == EdgeChecks::kCertified
                         ? certified_free(a.data(), b.data())
                         : sampled_free(a.data(), b.data(), segments(s1, s2, a.data(), b.data()));
  count(valid ? 1 : 0, valid ? 0 : 1);
  return valid;
}

bool MotionValidator::sampled_free(const float* a, const float* b, int segments) const {
  // The end state first, on the host: most motions an RRT tries end in collision, and
  // those never cost a GPU call.
  std::uint8_t end = 1;
  checker_->host_checker()->check(b, 1, &end);
  if (end != 0) return false;
  const auto by_levels = [&] {
    std::uint8_t between = 1;
    return host_local_.check_motions(a, b, 1, &segments, &between) && between == 0;
  };
  if (checker_->configurations_per_call_cost() == 0) return by_levels();  // calls cost nothing
  int way = 0;
  {
    const std::lock_guard<std::mutex> lock(way_.mutex);
    const std::size_t call = way_.calls++;
    if (way_.timed[0] < 4 || way_.timed[1] < 4) {
      way = way_.timed[1] < way_.timed[0] ? 1 : 0;
    } else {
      way = way_.mean_seconds[1] < way_.mean_seconds[0] ? 1 : 0;
      if (call % 16 == 0) way = 1 - way;  // keep the other way's mean current
    }
  }
  const auto started = std::chrono::steady_clock::now();
  const bool valid =
      way == 0 ? by_levels() : local_.last_valid_fraction(a, b, segments, true) == 1.0;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::lock_guard<std::mutex> lock(way_.mutex);
  double& mean = way_.mean_seconds[way];
  // A slow running mean: a motion's cost swings tenfold between one that collides at a
  // coarse level and a free one, and a fast mean would follow the last few.
  mean = way_.timed[way]++ == 0 ? seconds : 0.95 * mean + 0.05 * seconds;
  return valid;
}

bool MotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                  std::pair<ompl::base::State*, double>& lastValid) const {
  const int width = scene_.space.width();
  std::vector<float> a(width), b(width);
  state_to_row(scene_, s1, a.data());
  state_to_row(scene_, s2, b.data());
  // Beyond the bounds the end state is invalid; samples between two states within the
  // (convex) bounds stay within them.
  const bool certified = edges_ == EdgeChecks::kCertified;
  if (certified && si_->satisfiesBounds(s2) && certified_free(a.data(), b.data())) {
    count(1, 0);
    return true;
  }
  const int n = segments(s1, s2, a.data(), b.data());
  double fraction =
      si_->satisfiesBounds(s2) ? local_.last_valid_fraction(a.data(), b.data(), n, false) : -1;
  if (fraction == 1.0 && !certified) {
    count(1, 0);
    return true;
  }
  count(0, 1);
  if (fraction < 0 || fraction == 1.0) {
    // Only the end state is out of bounds (or, certified, no sample collides but the
    // motion is not certified): the last sample before it.
    fraction = static_cast<double>(n - 1) / n;
  }
  if (certified && fraction > 0) {
    std::vector<float> last(width);
    scene_.space.interpolate(a.data(), b.data(), fraction, last.data());
    if (!certified_free(a.data(), last.data())) fraction = 0;
  }
  lastValid.second = fraction;
  if (lastValid.first) si_->getStateSpace()->interpolate(s1, s2, fraction, lastValid.first);
  return false;
}

void MotionValidator::checkMotions(
    const std::vector<std::pair<const ompl::base::State*, const ompl::base::State*>>& motions,
    std::vector<std::uint8_t>* valid) const {
  const std::size_t n = motions.size(), width = scene_.space.width();
  std::vector<float> from(n * width), to(n * width);
  for (std::size_t i = 0; i < n; ++i) {
    state_to_row(scene_, motions[i].first, &from[i * width]);
    state_to_row(scene_, motions[i].second, &to[i * width]);
  }
  std::vector<std::uint8_t> invalid(n, 0), end(n, 0);
  if (edges_ == EdgeChecks::kCertified) {
    certifier_.check_motions(from.data(), to.data(), n, invalid.data());  // ends included
  } else {
    std::vector<int> segment_count(n);
    for (std::size_t i = 0; i < n; ++i) {
      segment_count[i] =
          segments(motions[i].first, motions[i].second, &from[i * width], &to[i * width]);
    }
    local_.check_motions(from.data(), to.data(), n, segment_count.data(), invalid.data());
    checker_->check(to.data(), n, end.data());
  }
  valid->assign(n, 0);
  std::size_t valid_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool ok = !invalid[i] && !end[i] && si_->satisfiesBounds(motions[i].second);
    (*valid)[i] = ok ? 1 : 0;
    valid_count += ok;
  }
  count(valid_count, n - valid_count);
}

void MotionValidator::count(std::size_t valid, std::size_t invalid) const {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  valid_ += valid;
  invalid_ += invalid;
}

}  // namespace gplanner::ompl_adapters
