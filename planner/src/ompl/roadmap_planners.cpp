#include "gplanner/planner/ompl/roadmap_planners.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathGeometric.h>

#include <limits>
#include <string>

#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {

namespace ob = ompl::base;

RoadmapOmplPlanner::RoadmapOmplPlanner(const ob::SpaceInformationPtr& si, const Scene& scene,
                                       CollisionChecker* checker, RoadmapStrategy strategy)
    : ob::Planner(si, strategy == RoadmapStrategy::kPrm ? "gplanner PRM" : "gplanner LazyPRM"),
      scene_(scene),
      checker_(checker),
      strategy_(strategy),
      options_(plan_options(scene)) {
  specs_.recognizedGoal = ob::GOAL_SAMPLEABLE_REGION;
  specs_.multithreaded = false;
  specs_.optimizingPaths = false;
  neighbors_ = make_neighbor_finder(make_metric(scene.space, scene.planner), checker->backend());
  addPlannerProgressProperty("milestones INTEGER", [this] { return std::to_string(milestones_); });
  addPlannerProgressProperty("edges INTEGER", [this] { return std::to_string(edges_); });
  addPlannerProgressProperty("valid edges INTEGER",
                             [this] { return std::to_string(valid_edges_); });
}

RoadmapOmplPlanner::~RoadmapOmplPlanner() { free_data_states(); }

void RoadmapOmplPlanner::free_data_states() const {
  for (ob::State* state : data_states_) si_->freeState(state);
  data_states_.clear();
}

void RoadmapOmplPlanner::clear() {
  ob::Planner::clear();
  planner_.reset();
  last_ = {};
  milestones_ = edges_ = valid_edges_ = 0;
  free_data_states();
}

ob::PlannerStatus RoadmapOmplPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  const ob::State* start = pis_.nextStart();
  if (start == nullptr) return ob::PlannerStatus::INVALID_START;
  const ob::State* goal = pis_.nextGoal(ptc);
  if (goal == nullptr) return ob::PlannerStatus::INVALID_GOAL;
  const int width = scene_.space.width();
  std::vector<float> a(width), b(width);
  state_to_row(scene_, start, a.data());
  state_to_row(scene_, goal, b.data());

  PlanOptions options = options_;
  options.time_limit_s = std::numeric_limits<double>::infinity();
  options.should_stop = [&ptc] { return ptc.eval(); };
  options.progress = [this](const PlanProgress& p) {
    milestones_ = p.milestones;
    edges_ = p.edges;
    valid_edges_ = p.edges_valid;
  };
  if (!planner_) {
    planner_ =
        std::make_unique<RoadmapPlanner>(scene_, checker_, neighbors_.get(), strategy_, options);
  }
  planner_->set_options(options);
  last_ = planner_->solve(a.data(), b.data());
  milestones_ = last_.milestones;
  edges_ = last_.edges;
  if (!last_.solved) return ob::PlannerStatus::TIMEOUT;
  auto path = std::make_shared<ompl::geometric::PathGeometric>(si_);
  ob::State* state = si_->allocState();
  for (std::size_t i = 0; i < last_.path.size() / width; ++i) {
    row_to_state(scene_, &last_.path[i * width], state);
    path->append(state);
  }
  si_->freeState(state);
  pdef_->addSolutionPath(path, false, 0.0, getName());
  return ob::PlannerStatus::EXACT_SOLUTION;
}

void RoadmapOmplPlanner::getPlannerData(ob::PlannerData& data) const {
  ob::Planner::getPlannerData(data);
  if (!planner_) return;
  free_data_states();
  const Roadmap& roadmap = planner_->roadmap();
  for (std::size_t v = 0; v < roadmap.vertex_count(); ++v) {
    ob::State* state = si_->allocState();
    row_to_state(scene_, roadmap.vertex(v), state);
    data_states_.push_back(state);
    data.addVertex(ob::PlannerDataVertex(state));
  }
  for (const RoadmapEdge& e : roadmap.edges()) {
    if (e.state == EdgeState::kInvalid) continue;
    data.addEdge(e.a, e.b, ob::PlannerDataEdge(), ob::Cost(e.length));
    data.addEdge(e.b, e.a, ob::PlannerDataEdge(), ob::Cost(e.length));
  }
}

}  // namespace gplanner::ompl_adapters
