#pragma once
// Our PRM and lazy PRM (RoadmapPlanner: batched milestone and edge checks, k-NN on the
// GPU with the gpu backend) as OMPL planners, for OMPL code and ompl::tools::Benchmark:
// they take their start and goal from the problem definition, honour the termination
// condition, add the path to the problem definition, fill PlannerData with the roadmap
// and report progress properties (milestones, edges, valid edges). The roadmap is kept
// between solve() calls (PRM answers later queries from it) until clear().

#include <ompl/base/Planner.h>

#include <memory>
#include <vector>

#include "gplanner/planner/checkers/collision_checker.h"
#include "gplanner/planner/planning/roadmap_planner.h"

namespace gplanner {

struct Scene;

namespace ompl_adapters {

class RoadmapOmplPlanner : public ompl::base::Planner {
 public:
  // si: a space of make_state_space(scene); scene and checker must outlive the planner.
  RoadmapOmplPlanner(const ompl::base::SpaceInformationPtr& si, const Scene& scene,
                     CollisionChecker* checker, RoadmapStrategy strategy);
  ~RoadmapOmplPlanner() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  // The settings used (from the scene's planner settings); change before solve().
  PlanOptions& options() { return options_; }
  const PlanResult& last_result() const { return last_; }

 private:
  void free_data_states() const;

  const Scene& scene_;
  CollisionChecker* checker_;
  RoadmapStrategy strategy_;
  PlanOptions options_;
  std::unique_ptr<NeighborFinder> neighbors_;
  std::unique_ptr<RoadmapPlanner> planner_;
  PlanResult last_;
  std::size_t milestones_ = 0, edges_ = 0, valid_edges_ = 0;  // progress properties
  mutable std::vector<ompl::base::State*> data_states_;       // states lent to PlannerData
};

// PRM: every new edge checked in one batch per round.
class Prm : public RoadmapOmplPlanner {
 public:
  Prm(const ompl::base::SpaceInformationPtr& si, const Scene& scene, CollisionChecker* checker)
      : RoadmapOmplPlanner(si, scene, checker, RoadmapStrategy::kPrm) {}
};

// Lazy PRM: edges checked only on candidate paths, all edges of a path in one batch.
class LazyPrm : public RoadmapOmplPlanner {
 public:
  LazyPrm(const ompl::base::SpaceInformationPtr& si, const Scene& scene, CollisionChecker* checker)
      : RoadmapOmplPlanner(si, scene, checker, RoadmapStrategy::kLazyPrm) {}
};

}  // namespace ompl_adapters
}  // namespace gplanner
