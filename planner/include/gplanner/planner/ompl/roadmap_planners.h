#pragma once
// Our PRM and lazy PRM (RoadmapPlanner: batched milestone and edge checks, k-NN on the
// GPU with the gpu backend) as OMPL planners, for OMPL code and ompl::tools::Benchmark,
// following OMPL's conventions:
// - start and goal from the problem definition, the path added to it, PlannerData
//   filled with the roadmap; the roadmap kept between solve() calls (PRM answers later
//   queries from it) until clear();
// - the termination condition polled between short slices of every stage;
// - seeded from OMPL's random numbers: a planner draws the seed of each new roadmap (the
//   first solve() after construction or clear()) from its own ompl::RNG, itself seeded
//   by OMPL's global seed (ompl::RNG::setSeed, before the planner is made), so that the
//   runs of a Benchmark differ and a program that sets OMPL's seed repeats exactly; a
//   seed set explicitly (the "seed" parameter, or options().seed, not 0) is used as is;
// - parameters declared (params(): "milestones", "max_nearest_neighbors" as OMPL's PRM
//   names k, "shortcut_rounds" (0: no shortcutting), "certified_edges",
//   "certify_path", "seed", and with lazy PRM "lazy_batch_paths"), which Benchmark logs
//   and params().setParam() sets;
// - progress properties as OMPL's PRM names them ("iterations INTEGER": rounds,
//   "milestone count INTEGER", "edge count INTEGER", "best cost REAL": the shortest
//   path's length), and ours
//   ("valid edge count INTEGER", "seed INTEGER");
// - messages through OMPL's console (OMPL_INFORM at the start and end of solve());
// - motions sampled at the space information's resolution
//   (si->setStateValidityCheckingResolution, the state space's longest valid segment
//   fraction), as OMPL's validators sample them; the edges the planner checked are added
//   to the space information's motion validator's counters, so that Benchmark's "valid
//   segment fraction" covers our planners too.

#include <ompl/base/Planner.h>
#include <ompl/util/RandomNumbers.h>

#include <atomic>
#include <limits>
#include <memory>
#include <utility>
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

  void setup() override;
  using ompl::base::Planner::solve;  // solve(seconds) too
  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  // The settings used (from the scene's planner settings, the seed 0: drawn from
  // ompl::RNG); change before solve(). The declared parameters set the same fields.
  PlanOptions& options() { return options_; }
  const PlanResult& last_result() const { return last_; }
  // The seed of the current roadmap (0 before the first solve()).
  unsigned long long roadmap_seed() const { return roadmap_seed_; }

 private:
  void free_data_states() const;
  void declare_params();
  // The roadmap's valid and invalid edges.
  std::pair<std::size_t, std::size_t> checked_edges() const;

  const Scene& scene_;
  CollisionChecker* checker_;
  RoadmapStrategy strategy_;
  PlanOptions options_;
  ompl::RNG rng_;  // draws roadmap seeds
  std::atomic<unsigned long long> roadmap_seed_{0};
  std::unique_ptr<NeighborFinder> neighbors_;
  std::unique_ptr<RoadmapPlanner> planner_;
  PlanResult last_;
  // Progress properties, read by Benchmark's thread while solve() runs.
  std::atomic<std::size_t> rounds_{0}, milestones_{0}, edges_{0}, valid_edges_{0};
  std::atomic<double> best_cost_{std::numeric_limits<double>::infinity()};  // shortest path
  mutable std::vector<ompl::base::State*> data_states_;  // states lent to PlannerData
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
