#include "harness/error_time_truth.h"

#include <algorithm>

#include "gplanner/planner/scene/scene.h"

namespace gplan {
namespace {

gplanner::CertifiedMotionOptions certified_at(double step_m) {
  gplanner::CertifiedMotionOptions options;
  options.step = step_m;
  return options;  // finest_step: its default, step / 1024
}

gplanner::LocalPlannerOptions sampled_at(double step_m) {
  gplanner::LocalPlannerOptions options;
  options.max_displacement = step_m;
  return options;
}

}  // namespace

GroundTruth::GroundTruth(const gplanner::Scene& scene, double step_m)
    : scene_(scene),
      step_(step_m),
      fcl_(scene, /*threads=*/0),
      certified_(scene, &fcl_, certified_at(step_m)),
      sampled_(scene, &fcl_, sampled_at(step_m)) {}

std::vector<std::uint8_t> GroundTruth::states(const float* configurations, std::size_t n) {
  std::vector<std::uint8_t> colliding(n);
  fcl_.check(configurations, n, colliding.data());
  return colliding;
}

std::vector<MotionTruth> GroundTruth::motions(const float* from, const float* to, std::size_t n,
                                              const std::function<bool()>& stop) {
  const std::size_t width = scene_.space.width();
  certified_.set_stop(stop);
  sampled_.set_stop(stop);
  std::vector<std::uint8_t> not_certified(n);
  if (!certified_.check_motions(from, to, n, not_certified.data())) return {};
  // The motions not certified: their ends and their samples at the fine step.
  std::vector<std::size_t> open;
  std::vector<float> open_from, open_to;
  for (std::size_t i = 0; i < n; ++i) {
    if (!not_certified[i]) continue;
    open.push_back(i);
    open_from.insert(open_from.end(), from + i * width, from + (i + 1) * width);
    open_to.insert(open_to.end(), to + i * width, to + (i + 1) * width);
  }
  std::vector<std::uint8_t> sample_collides(open.size()), from_collides(open.size()),
      to_collides(open.size());
  if (!open.empty()) {
    if (!sampled_.check_motions(open_from.data(), open_to.data(), open.size(),
                                sample_collides.data()))
      return {};
    fcl_.check(open_from.data(), open.size(), from_collides.data());
    fcl_.check(open_to.data(), open.size(), to_collides.data());
  }
  std::vector<MotionTruth> truth(n, MotionTruth::kFree);
  for (std::size_t k = 0; k < open.size(); ++k) {
    truth[open[k]] = sample_collides[k] || from_collides[k] || to_collides[k]
                         ? MotionTruth::kColliding
                         : MotionTruth::kUndecided;
  }
  return truth;
}

std::string GroundTruth::path(const std::vector<float>& path, const std::function<bool()>& stop) {
  const std::size_t width = scene_.space.width();
  const std::size_t waypoints = path.size() / width;
  if (waypoints < 2) {
    // One waypoint: a state, no motion.
    return waypoints == 1 && !states(path.data(), 1)[0] ? "pass" : "fail";
  }
  const std::size_t segments = waypoints - 1;
  const std::vector<MotionTruth> truth = motions(path.data(), path.data() + width, segments, stop);
  if (truth.empty()) return "";
  if (std::count(truth.begin(), truth.end(), MotionTruth::kColliding)) return "fail";
  if (std::count(truth.begin(), truth.end(), MotionTruth::kUndecided)) return "undecided";
  return "pass";
}

}  // namespace gplan
