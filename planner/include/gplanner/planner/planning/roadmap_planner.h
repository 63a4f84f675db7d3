#pragma once
// PRM and lazy PRM over one roadmap, as G-Planner runs them on the GPU: milestones are
// sampled and checked in one batch per round, joined to their k nearest neighbours
// (GPU k-NN), and then
// - PRM (multi-query) checks every new edge in one batch and searches the valid ones;
// - lazy PRM (single query) searches all edges not known invalid, checks every
//   unchecked edge of the found path, and of the next shortest paths found with those
//   edges set aside, in one batch, drops the invalid ones and searches again, until a
//   path is valid or none is left (then the roadmap grows).
// The found path is shortcut with batched checks and re-checked at a finer resolution.
// Seeded and deterministic for a given seed (with a deterministic checker).

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <unordered_set>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/certified_motions.h"
#include "gplanner/planner/planning/goal_distances.h"
#include "gplanner/planner/planning/graph_search.h"
#include "gplanner/planner/planning/local_planner.h"
#include "gplanner/planner/planning/milestone_sampler.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/plan_options.h"
#include "gplanner/planner/planning/plan_result.h"
#include "gplanner/planner/planning/roadmap.h"
#include "gplanner/planner/planning/timed_batch_size.h"

namespace gplanner {

struct Scene;

enum class RoadmapStrategy { kPrm, kLazyPrm };

// "prm" / "lazyprm"; parse returns false for other names.
const char* strategy_name(RoadmapStrategy strategy);
bool parse_strategy(const std::string& name, RoadmapStrategy* strategy);

class RoadmapPlanner {
 public:
  // scene, checker and neighbors must outlive the planner.
  RoadmapPlanner(const Scene& scene, CollisionChecker* checker, NeighborFinder* neighbors,
                 RoadmapStrategy strategy, const PlanOptions& options);

  // Plans from start to goal (each shape [width], free: callers check them first),
  // growing the roadmap until a path is found, the time limit passes, or should_stop
  // says so.
  PlanResult solve(const float* start, const float* goal);

  const Roadmap& roadmap() const { return roadmap_; }
  // Starts from a saved roadmap: its edge states are kept (an edge is certified by the
  // final re-check before a path uses it all the same), its edge lengths recomputed
  // under the metric, and its milestones checked at the next solve() (a milestone found
  // colliding loses its edges), so that a file, however made, cannot lead through an
  // obstacle.
  void set_roadmap(Roadmap roadmap);
  const PlanOptions& options() const { return options_; }
  // New settings for the next solve() (the roadmap stays; the local planner keeps the
  // resolution it was made with, the certified motions their step). Edges that passed
  // the final check pass it again where the check changes between fine and certified.
  void set_options(const PlanOptions& options);
  RoadmapStrategy strategy() const { return strategy_; }

 private:
  std::size_t add_milestones(std::size_t count, PlanResult* result);
  // Joins the milestones not yet joined to their nearest; false when it stopped first
  // (stop_reason set).
  bool connect(PlanResult* result);
  void check_edges(const std::vector<std::uint32_t>& edges, PlanResult* result);
  // Checks the loaded milestones not yet checked, in slices; the edges of those found
  // colliding become invalid. False where the stop came first (the rest wait).
  bool check_loaded_milestones(PlanResult* result);
  // The motions along `edges` checked by `motions` (invalid: one entry per edge); false
  // when its stop condition ended the check part way.
  bool check_edge_motions(MotionChecker* motions, const std::vector<std::uint32_t>& edges,
                          std::vector<std::uint8_t>* invalid) const;
  // Whether the path returned is certified (PlanOptions::certify_path, or edges certified
  // throughout).
  bool certifies_path() const;
  // The path's edges whose state is unknown.
  std::vector<std::uint32_t> unknown_edges(const GraphPath& path) const;
  // Lazy PRM: adds to `batch` (the shortest path's unknown edges) those of the next
  // shortest paths, up to options_.lazy_batch_paths paths in all, searched from `s` to
  // to_goal's goal (to_goal: every vertex's cost to it); shortest_vertices: the shortest
  // path's vertex count.
  void add_next_paths(const GoalDistances& to_goal, std::uint32_t s, std::size_t shortest_vertices,
                      std::vector<std::uint32_t>* batch, PlanResult* result);
  // Why planning must stop now ("stopped": should_stop; "time limit"), or null.
  const char* why_stop() const;
  // Whether it must, the reason then put in result->stop_reason.
  bool out_of_time(PlanResult* result) const;
  void report(const char* stage, const PlanResult& result) const;
  // Sets edge e's state, keeping valid_edges_.
  void set_edge_state(std::uint32_t e, EdgeState state);
  double elapsed() const;

  const Scene& scene_;
  CollisionChecker* checker_;
  NeighborFinder* neighbors_;
  RoadmapStrategy strategy_;
  PlanOptions options_;
  LocalPlanner local_;
  CertifiedMotions certifier_;
  // The path's re-check and the shortcuts' check, at the resolution refined by
  // PlanOptions::final_check_refinement: made with the planner and again by set_options()
  // (its motion bound goes over every vertex of the robot's meshes), not per solve.
  std::optional<LocalPlanner> fine_;
  MilestoneSampler sampler_;
  Roadmap roadmap_;
  std::mt19937_64 rng_;
  // Sampling attempts made and milestones found so far: their ratio sizes batches.
  std::size_t attempts_ = 0, attempts_found_ = 0;
  // Milestones found beyond a round's count, the next round's first (shape [*, width]).
  std::vector<float> surplus_;
  // Milestones [0, connected_) have been joined to their neighbours.
  std::size_t connected_ = 0;
  // The roadmap's edges known valid, for the progress reports (counting them over a
  // roadmap of 400,000 edges at each report cost a piano plan a few milliseconds).
  std::size_t valid_edges_ = 0;
  // Milestones [0, loaded_unchecked_) of a loaded roadmap still to be checked.
  std::size_t loaded_unchecked_ = 0;
  // Edges that passed the final check, certified or at the fine resolution (in the
  // roadmap as it is now).
  std::unordered_set<std::uint32_t> certified_;
  std::chrono::steady_clock::time_point started_;
  // Every long stage runs in slices of about slice_seconds(options) (milestone batches,
  // k-NN chunks, checker calls; the searches poll it), with this stop between them: a
  // stop, or the time limit passed.
  std::function<bool()> stop_;
  TimedBatchSize sampling_batch_;  // sampling attempts per checker call
  TimedBatchSize knn_batch_;       // new milestones per k-NN call
  // The last k-NN call, for a finder that searches all points each call: its points
  // and time, to tell whether the next one would end within the time limit.
  std::size_t knn_last_points_ = 0;
  double knn_last_seconds_ = 0;
};

}  // namespace gplanner
