#pragma once
// How a roadmap planner is asked to plan: seed, time limit, roadmap size, lazy batches,
// shortcutting, edge resolution, sampling, and the callbacks it reports to.

#include <cstddef>
#include <functional>
#include <string>

#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/milestone_sampler.h"

namespace gplanner {

// Reported after each stage of a round; planners call it from the planning thread.
struct PlanProgress {
  const char* stage;  // "milestones", "neighbours", "edges", "search", "shortcut"
  std::size_t round;
  std::size_t milestones;
  std::size_t edges;
  std::size_t edges_valid;
  double elapsed_s;
};

// Most free milestones a first round may ask for (gplan --milestones, the scene's
// planner.roadmap.milestones); memory bounds it further (roadmap_bytes).
inline constexpr std::size_t kMaxMilestones = 100000000;

// How a planner checks the edges of its roadmap: at samples of the edge resolution
// (LocalPlanner), or certified free along the whole motion (CertifiedMotions).
enum class EdgeChecks { kSampled, kCertified };
const char* edge_checks_name(EdgeChecks edges);  // "sampled", "certified"
bool parse_edge_checks(const std::string& name, EdgeChecks* edges);

struct PlanOptions {
  unsigned long long seed = 1;
  double time_limit_s = 30;
  std::size_t milestones = 2000;  // free ones the first round adds; later rounds double the roadmap
  int neighbors = 15;             // k
  // Lazy PRM: one batch checks the unknown edges of the shortest path and of up to this
  // many - 1 next shortest ones (1: the shortest path's only).
  int lazy_batch_paths = 64;
  int shortcut_rounds = 6;
  int shortcut_candidates = 256;
  // The found path is re-checked at the edge resolution divided by this (1: not at all)
  // before it is returned; a path that fails sends the search back to the roadmap.
  // (Only when certify_path is false.)
  int final_check_refinement = 10;
  EdgeChecks edges = EdgeChecks::kSampled;
  // The found path is certified free (CertifiedMotions) before it is returned; an edge
  // that fails is removed and the search goes on.
  bool certify_path = true;
  CertifiedMotionOptions certified;
  LocalPlannerOptions local;
  SamplerOptions sampler;  // how milestones are drawn
  // Batched RRT-Connect (TreePlanner): the longest extension under the planner's metric
  // (<= 0: a fifth of the space's extent, OMPL's RRTConnect default), and the extensions
  // checked a round (0: enough to fill a GPU call, or as many as the host has threads).
  double tree_range = 0;
  std::size_t tree_lanes = 0;
  // How long one slice of a long stage (a checker call, a k-NN chunk) should take, and so
  // how often a stop or the time limit is seen; 0: 2 % of the time limit, within
  // [20 ms, 250 ms]. Callers with no time limit but a stop condition (OMPL's) set it.
  double slice_s = 0;
  std::function<void(const PlanProgress&)> progress;
  // Polled often (between slices of every stage, each kept short): true stops planning
  // (OMPL's termination conditions, gplan's SIGINT), as the time limit does.
  std::function<bool()> should_stop;
};

// How long one slice of a long stage should take: slice_s, or 2 % of the time limit
// within [20 ms, 250 ms].
double slice_seconds(const PlanOptions& options);
// `options` with their calls sized to take a slice each (batch_seconds).
LocalPlannerOptions sliced(LocalPlannerOptions options, const PlanOptions& plan);
CertifiedMotionOptions sliced(CertifiedMotionOptions options, const PlanOptions& plan);
// `options` as a planner's own motion checks take them: sliced, and, unless set, with
// levels of at least kLevelSamplesPerThread samples for each of the host's threads
// (LocalPlannerOptions::least_level_samples: on a 16-core H200 host, MotionBenchMaker's
// first 20 problems of four scenarios, the cpu backend planned the same paths 1.2x to
// 1.8x sooner with 8 than with none, and 1.2x to 1.7x with 2).
inline constexpr std::size_t kLevelSamplesPerThread = 8;
LocalPlannerOptions planner_local(LocalPlannerOptions options, const PlanOptions& plan);
// `options` at `refinement` times the resolution (the fine re-check's).
LocalPlannerOptions refined(LocalPlannerOptions options, int refinement);

struct Scene;
// The options a scene's planner settings give (seed, time limit, roadmap, shortcut,
// edge resolution, sampler).
PlanOptions plan_options(const Scene& scene);

}  // namespace gplanner
