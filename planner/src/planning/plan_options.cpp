#include "gplanner/planner/planning/plan_options.h"

#include <algorithm>

#include "gplanner/common/parallel_for.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner {

// 2 % of the time limit, within [20 ms, 250 ms], so that the time limit is kept within
// the larger of 5 % and 100 ms and a stop (should_stop: SIGINT, OMPL's conditions) is
// honoured within about a slice, while every call stays long against its fixed costs
// (with slices of at most 40 ms, lazy PRM on 16 cores took up to 1.8x its time at
// bc00c10 on the cpu backend: benchmarks/RESULTS.md, "The time limit").
double slice_seconds(const PlanOptions& options) {
  if (options.slice_s > 0) return options.slice_s;
  return std::clamp(0.02 * options.time_limit_s, 0.02, 0.25);
}

LocalPlannerOptions sliced(LocalPlannerOptions options, const PlanOptions& plan) {
  options.batch_seconds = slice_seconds(plan);
  return options;
}

CertifiedMotionOptions sliced(CertifiedMotionOptions options, const PlanOptions& plan) {
  options.batch_seconds = slice_seconds(plan);
  return options;
}

LocalPlannerOptions planner_local(LocalPlannerOptions options, const PlanOptions& plan) {
  options = sliced(options, plan);
  if (options.least_level_samples == 0)
    options.least_level_samples = kLevelSamplesPerThread * resolve_thread_count(0);
  return options;
}

LocalPlannerOptions refined(LocalPlannerOptions options, int refinement) {
  options.resolution_fraction /= refinement;
  options.max_displacement /= refinement;
  return options;
}

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
