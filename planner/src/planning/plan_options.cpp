#include "gplanner/planner/planning/plan_options.h"

#include "gplanner/planner/scene/scene.h"

namespace gplanner {

PlanOptions plan_options(const Scene& scene) {
  const PlannerSettings& s = scene.planner;
  PlanOptions options;
  options.seed = static_cast<unsigned long long>(s.number("seed"));
  options.time_limit_s = s.number("time_limit_s");
  options.milestones = static_cast<std::size_t>(s.number("roadmap.milestones"));
  options.neighbors = static_cast<int>(s.number("roadmap.neighbors"));
  options.lazy_batch_paths = static_cast<int>(s.number("roadmap.lazy_batch_paths"));
  options.shortcut_rounds = static_cast<int>(s.number("shortcut.rounds"));
  options.shortcut_candidates = static_cast<int>(s.number("shortcut.candidates"));
  options.local.resolution_fraction = s.number("edge_resolution");
  options.local.max_displacement = s.number("max_displacement");
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
