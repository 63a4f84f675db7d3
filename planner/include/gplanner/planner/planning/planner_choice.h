#pragma once
// The planners gplan plan, gplan bench and the Python module run by name: the roadmap
// planner's lazy PRM and PRM (RoadmapPlanner), batched RRT-Connect (TreePlanner), and
// "auto", the default, which picks between them by what was asked and the robot:
// - where a roadmap is loaded, saved or sized (the caller says so), lazy PRM;
// - for a rigid body flying free (a floating or planar base and no joint: the piano, the
//   helicopter, OMPL.app's puzzles), lazy PRM: between rooms whose doorway only a few
//   poses pass, its batched roadmap finds the way where almost every tree extension hits
//   a wall (on the H200 at db271f9: the helicopter 0.13 s against the trees' 0.6 to 3.7 s;
//   the pianos unsolved by the trees in 30 s on the cpu backend);
// - otherwise (arms, mobile manipulators, humanoids) batched RRT-Connect, whose trees grow
//   from the start and the goal into the free space about them (H200, db271f9: pr2_reach
//   43 to 136 ms against lazy PRM's 0.7 s, the humanoid 27 against 66 ms; MotionBenchMaker's
//   shelves and cage, where lazy PRM's uniform milestones rarely reach a start in a shelf:
//   70 of 70 solved against 65).
// The choice never depends on timing: a seed plans the same path every time (with a
// deterministic checker).

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

// Runs the planner asked for, auto resolved as above.
class ChosenPlanner {
 public:
  // scene, checker and neighbors must outlive it; neighbors may be null where
  // rrtconnect runs.
  // with_roadmap: a roadmap is loaded, saved or sized (auto then takes lazy PRM).
  ChosenPlanner(const Scene& scene, CollisionChecker* checker, NeighborFinder* neighbors,
                PlannerKind kind, bool with_roadmap, const PlanOptions& options);
  ~ChosenPlanner();

  PlanResult solve(const float* start, const float* goal);

  PlannerKind asked() const { return asked_; }
  // The planner that runs (auto resolved).
  PlannerKind used() const { return used_; }
  // Why auto chose it ("" where the planner was named).
  const std::string& reason() const { return reason_; }
  // The roadmap planner where lazyprm or prm runs (null otherwise): for loading and
  // saving roadmaps.
  RoadmapPlanner* roadmap_planner() { return roadmap_.get(); }

 private:
  PlannerKind asked_, used_;
  std::unique_ptr<TreePlanner> tree_;
  std::unique_ptr<RoadmapPlanner> roadmap_;
  std::string reason_;
};

}  // namespace gplanner
