#pragma once
// The planners gplan plan, gplan bench and the Python module run by name: the roadmap
// planner's lazy PRM and PRM (RoadmapPlanner), batched RRT-Connect (TreePlanner), and
// "auto", the default, which picks between them:
// - where a roadmap is loaded, saved or sized (the caller says so), lazy PRM;
// - otherwise batched RRT-Connect, whose trees grow from the start and the goal (on
//   MotionBenchMaker's shelves and cage, where lazy PRM's uniform milestones rarely reach
//   the start or the goal); where its trees are trapped (fewer than kTrappedGrowth nodes
//   added per extension: narrow passages all about, as the piano's and the helicopter's),
//   lazy PRM with the time left, its milestones drawn as the scene's sampler settings
//   say (bridges, rotations along the way).
// The choice depends on the seed and the scene only, never on timing: a seed plans the
// same path every time (with a deterministic checker).

#include <memory>
#include <string>

#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/planning/tree_planner.h"

namespace gplanner {

enum class PlannerKind { kAuto, kLazyPrm, kPrm, kRrtConnect };

// "auto", "lazyprm", "prm", "rrtconnect"; parse returns false for other names.
const char* planner_name(PlannerKind kind);
bool parse_planner(const std::string& name, PlannerKind* kind);
// The names, for messages: "auto, lazyprm, prm, rrtconnect".
const char* planner_names();
// Whether the planner may run on a roadmap, and so takes roadmap options (milestones,
// roadmap files): all but rrtconnect.
bool keeps_roadmap(PlannerKind kind);

// auto hands over to lazy PRM below this growth (TreePlanner, tree_trapped_growth): 0.15
// nodes per extension. Measured on the cpu backend at 2 lanes: the piano 0.02, the
// helicopter 0.10, the humanoid 0.27, MotionBenchMaker's shelves and cage 0.26 to 0.40.
inline constexpr double kTrappedGrowth = 0.15;

// Runs the planner asked for, auto resolved as above.
class ChosenPlanner {
 public:
  // scene, checker and neighbors must outlive it; neighbors may be null for rrtconnect.
  // with_roadmap: a roadmap is loaded, saved or sized (auto then takes lazy PRM).
  ChosenPlanner(const Scene& scene, CollisionChecker* checker, NeighborFinder* neighbors,
                PlannerKind kind, bool with_roadmap, const PlanOptions& options);
  ~ChosenPlanner();

  PlanResult solve(const float* start, const float* goal);

  PlannerKind asked() const { return asked_; }
  // The planner that gave the last solve()'s answer (before any: the first to run).
  PlannerKind used() const { return used_; }
  // Why auto chose it ("" where the planner was named).
  const std::string& reason() const { return reason_; }
  // The roadmap planner, made where lazyprm or prm runs or auto may hand over (null
  // otherwise): for loading and saving roadmaps.
  RoadmapPlanner* roadmap_planner() { return roadmap_.get(); }

 private:
  const Scene& scene_;
  CollisionChecker* checker_;
  NeighborFinder* neighbors_;
  PlannerKind asked_, used_;
  PlanOptions options_;
  std::unique_ptr<TreePlanner> tree_;
  std::unique_ptr<RoadmapPlanner> roadmap_;
  std::string reason_;
};

}  // namespace gplanner
