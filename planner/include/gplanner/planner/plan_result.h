#pragma once
// What a planner reports: the path, and where the time went.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "gplanner/planner/local_planner.h"
#include "gplanner/planner/milestone_sampler.h"

namespace gplanner {

// Seconds per stage of a plan.
struct PlanTimes {
  double sampling = 0;      // drawing milestones
  double state_checks = 0;  // checking milestones (batches)
  double knn = 0;           // nearest neighbours for the roadmap's edges
  double search = 0;        // graph search
  double edge_checks = 0;   // checking edges (batches)
  double shortcutting = 0;  // shortening the found path (batched checks)
  double total = 0;         // the whole call
};

// Reported after each stage of a round; planners call it from the planning thread.
struct PlanProgress {
  const char* stage;  // "milestones", "neighbours", "edges", "search", "shortcut"
  std::size_t round;
  std::size_t milestones;
  std::size_t edges;
  std::size_t edges_valid;
  double elapsed_s;
};

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
  int final_check_refinement = 10;
  LocalPlannerOptions local;
  SamplerOptions sampler;  // how milestones are drawn
  std::function<void(const PlanProgress&)> progress;
  // Polled between stages: true stops planning (OMPL's termination conditions).
  std::function<bool()> should_stop;
};

struct Scene;
// The options a scene's planner settings give (seed, time limit, roadmap, shortcut,
// edge resolution, sampler).
PlanOptions plan_options(const Scene& scene);

struct PlanResult {
  bool solved = false;
  std::vector<float> path;  // shape [waypoints, width]: start ... goal
  double length = 0;        // metric length of the path
  double length_before_shortcut = 0;
  PlanTimes times;
  std::size_t rounds = 0;
  std::size_t milestones = 0;  // roadmap vertices, start and goal included
  std::size_t edges = 0;
  std::size_t edges_checked = 0;
  std::size_t states_checked = 0;
  std::size_t samples_checked = 0;  // edge samples
  std::size_t searches = 0;         // graph searches
  std::size_t edge_batches = 0;     // checker calls for edges, shortcuts and the fine re-check
  std::string stop_reason;          // "solved", "time limit", "stopped"
};

}  // namespace gplanner
