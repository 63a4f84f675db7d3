#include "gplanner/planner/planning/plan_options.h"

#include "gplanner/planner/scene/scene.h"

namespace gplanner {

PlanOptions plan_options(const Scene& scene) {
  const PlannerSettings& s = scene.planner;
  PlanOptions options;
  options.seed = s.seed;
  options.time_limit_s = s.time_limit_s;
  options.milestones = s.roadmap.milestones;
  options.neighbors = s.roadmap.neighbors;
  options.lazy_batch_paths = s.roadmap.lazy_batch_paths;
  options.shortcut_rounds = s.shortcut.rounds;
  options.shortcut_candidates = s.shortcut.candidates;
  options.local.resolution_fraction = s.edge_resolution;
  options.local.max_displacement = s.max_displacement;
  options.sampler = sampler_options(s);
  return options;
}

const char* edge_checks_name(EdgeChecks edges) {
  return edges == EdgeChecks::kCertified ? "certified" : "sampled";
}

bool parse_edge_checks(const std::string& name, EdgeChecks* edges) {
  if (name == "sampled") {
    *edges = EdgeChecks::kSampled;
  } else if (name == "certified") {
    *edges = EdgeChecks::kCertified;
  } else {
    return false;
  }
  return true;
}

}  // namespace gplanner
