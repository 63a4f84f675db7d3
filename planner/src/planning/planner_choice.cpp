#include "gplanner/planner/planning/planner_choice.h"

#include <cmath>
#include <stdexcept>

namespace gplanner {
namespace {

// The sum of two plans' stage times, GPU calls and counts, for a plan made of both.
void add_plan(const PlanResult& first, PlanResult* second) {
  PlanTimes& t = second->times;
  t.sampling += first.times.sampling;
  t.state_checks += first.times.state_checks;
  t.knn += first.times.knn;
  t.search += first.times.search;
  t.edge_checks += first.times.edge_checks;
  t.shortcutting += first.times.shortcutting;
  t.total += first.times.total;
  PlanGpuCalls& c = second->gpu_calls;
  c.state_checks += first.gpu_calls.state_checks;
  c.knn += first.gpu_calls.knn;
  c.edge_checks += first.gpu_calls.edge_checks;
  c.shortcutting += first.gpu_calls.shortcutting;
  c.total += first.gpu_calls.total;
  second->edges_checked += first.edges_checked;
  second->states_checked += first.states_checked;
  second->samples_checked += first.samples_checked;
  second->edge_batches += first.edge_batches;
}

}  // namespace

const char* planner_name(PlannerKind kind) {
  switch (kind) {
    case PlannerKind::kLazyPrm:
      return "lazyprm";
    case PlannerKind::kPrm:
      return "prm";
    case PlannerKind::kRrtConnect:
      return "rrtconnect";
    case PlannerKind::kAuto:
      break;
  }
  return "auto";
}

bool parse_planner(const std::string& name, PlannerKind* kind) {
  for (const PlannerKind k :
       {PlannerKind::kAuto, PlannerKind::kLazyPrm, PlannerKind::kPrm, PlannerKind::kRrtConnect}) {
    if (name == planner_name(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

const char* planner_names() { return "auto, lazyprm, prm, rrtconnect"; }

bool keeps_roadmap(PlannerKind kind) { return kind != PlannerKind::kRrtConnect; }

ChosenPlanner::ChosenPlanner(const Scene& scene, CollisionChecker* checker,
                             NeighborFinder* neighbors, PlannerKind kind, bool with_roadmap,
                             const PlanOptions& options)
    : scene_(scene),
      checker_(checker),
      neighbors_(neighbors),
      asked_(kind),
      used_(kind),
      options_(options) {
  if (kind == PlannerKind::kAuto) {
    used_ = with_roadmap ? PlannerKind::kLazyPrm : PlannerKind::kRrtConnect;
    reason_ =
        with_roadmap ? "a roadmap is loaded, saved or sized" : "a single query with no roadmap";
  }
  if (used_ != PlannerKind::kRrtConnect || kind == PlannerKind::kAuto) {
    if (neighbors == nullptr) throw std::invalid_argument("ChosenPlanner: no k-NN for a roadmap");
    roadmap_ = std::make_unique<RoadmapPlanner>(
        scene, checker, neighbors,
        used_ == PlannerKind::kPrm ? RoadmapStrategy::kPrm : RoadmapStrategy::kLazyPrm, options);
  }
  if (used_ == PlannerKind::kRrtConnect) {
    PlanOptions tree_options = options;
    if (kind == PlannerKind::kAuto) tree_options.tree_trapped_growth = kTrappedGrowth;
    tree_ = std::make_unique<TreePlanner>(scene, checker, tree_options);
  }
}

ChosenPlanner::~ChosenPlanner() = default;

PlanResult ChosenPlanner::solve(const float* start, const float* goal) {
  if (!tree_) return roadmap_->solve(start, goal);
  used_ = PlannerKind::kRrtConnect;
  PlanResult trees = tree_->solve(start, goal);
  if (trees.stop_reason != "trapped" || !roadmap_) return trees;
  // Trapped: lazy PRM with the time left.
  used_ = PlannerKind::kLazyPrm;
  const double growth = static_cast<double>(tree_->nodes_added()) / tree_->extensions();
  reason_ = "rrtconnect's trees were trapped (" +
            std::to_string(static_cast<int>(std::lround(100 * growth))) + " nodes per 100 of " +
            std::to_string(tree_->extensions()) + " extensions)";
  PlanOptions options = options_;
  options.time_limit_s = std::max(1e-3, options_.time_limit_s - trees.times.total);
  roadmap_->set_options(options);
  PlanResult result = roadmap_->solve(start, goal);
  add_plan(trees, &result);
  return result;
}

}  // namespace gplanner
