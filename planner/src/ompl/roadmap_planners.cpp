#include "gplanner/planner/ompl/roadmap_planners.h"

#include <stdexcept>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/util/Console.h>

#include <climits>
#include <cmath>
#include <limits>
#include <string>

#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"

namespace gplanner::ompl_adapters {
namespace {

namespace ob = ompl::base;

// A seed of 62 random bits (never 0) from an OMPL generator.
unsigned long long draw_seed(ompl::RNG* rng) {
  const auto high = static_cast<unsigned long long>(rng->uniformInt(0, INT_MAX));
  const auto low = static_cast<unsigned long long>(rng->uniformInt(1, INT_MAX));
  return high << 31 | low;
}

// Adds to a motion validator's counters, which OMPL keeps protected with no way to add
// from outside: a protected member named through a derived class gives a pointer to
// member of the base. Our planners check their edges themselves; this makes
// Benchmark's "valid segment fraction REAL" count them.
struct MotionCounters : ob::MotionValidator {
  static void add(ob::MotionValidator* validator, std::size_t valid, std::size_t invalid) {
    if (const auto* ours = dynamic_cast<const ompl_adapters::MotionValidator*>(validator)) {
      ours->add_counts(valid, invalid);  // under the lock its other callers take
      return;
    }
    validator->*(&MotionCounters::valid_) += static_cast<unsigned>(valid);
    validator->*(&MotionCounters::invalid_) += static_cast<unsigned>(invalid);
  }
};

}  // namespace

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
  require_scene_state_space(scene, si, name_.c_str());
  if (checker == nullptr) throw std::invalid_argument(name_ + ": no collision checker (null)");
  options_.seed = 0;  // drawn from rng_
  // A termination condition's deadline is unknown: slices short enough that one of
  // OMPL's time limits is kept within about 0.1 s, long enough for large batches.
  options_.slice_s = 0.05;
  neighbors_ = make_neighbor_finder(make_metric(scene.space, scene.planner), checker->backend(),
                                    nullptr, checker->gpu_device());
  declare_params();
  // OMPL's PRM's names first, then ours.
  addPlannerProgressProperty("iterations INTEGER", [this] { return std::to_string(rounds_); });
  addPlannerProgressProperty("best cost REAL", [this] { return std::to_string(best_cost_); });
  addPlannerProgressProperty("milestone count INTEGER",
                             [this] { return std::to_string(milestones_); });
  addPlannerProgressProperty("edge count INTEGER", [this] { return std::to_string(edges_); });
  addPlannerProgressProperty("valid edge count INTEGER",
                             [this] { return std::to_string(valid_edges_); });
  addPlannerProgressProperty("seed INTEGER", [this] { return std::to_string(roadmap_seed_); });
}

RoadmapOmplPlanner::~RoadmapOmplPlanner() { free_data_states(); }

void RoadmapOmplPlanner::declare_params() {
  PlanOptions* o = &options_;
  params_.declareParam<unsigned long>(
      "milestones", [o](unsigned long n) { o->milestones = n; },
      [o] { return static_cast<unsigned long>(o->milestones); });
  params_["milestones"].setRangeSuggestion("10:10:" + std::to_string(kMaxMilestones));
  params_.declareParam<unsigned>(
      "max_nearest_neighbors", [o](unsigned k) { o->neighbors = static_cast<int>(k); },
      [o] { return static_cast<unsigned>(o->neighbors); });
  params_["max_nearest_neighbors"].setRangeSuggestion("1:1000");
  params_.declareParam<unsigned>(
      "shortcut_rounds", [o](unsigned n) { o->shortcut_rounds = static_cast<int>(n); },
      [o] { return static_cast<unsigned>(o->shortcut_rounds); });
  params_["shortcut_rounds"].setRangeSuggestion("0:100");
  params_.declareParam<bool>(
      "certified_edges",
      [o](bool on) { o->edges = on ? EdgeChecks::kCertified : EdgeChecks::kSampled; },
      [o] { return o->edges == EdgeChecks::kCertified; });
  params_["certified_edges"].setRangeSuggestion("0,1");
  params_.declareParam<bool>(
      "certify_path", [o](bool on) { o->certify_path = on; }, [o] { return o->certify_path; });
  params_["certify_path"].setRangeSuggestion("0,1");
  params_.declareParam<double>(
      "slice_seconds", [o](double s) { o->slice_s = s; }, [o] { return o->slice_s; });
  params_["slice_seconds"].setRangeSuggestion("0.005:0.005:1");
  params_.declareParam<unsigned long long>(
      "seed", [o](unsigned long long seed) { o->seed = seed; }, [o] { return o->seed; });
  if (strategy_ == RoadmapStrategy::kLazyPrm) {
    params_.declareParam<unsigned>(
        "lazy_batch_paths", [o](unsigned n) { o->lazy_batch_paths = static_cast<int>(n); },
        [o] { return static_cast<unsigned>(o->lazy_batch_paths); });
    params_["lazy_batch_paths"].setRangeSuggestion("1:1024");
  }
}

void RoadmapOmplPlanner::free_data_states() const {
  for (ob::State* state : data_states_) si_->freeState(state);
  data_states_.clear();
}

void RoadmapOmplPlanner::setup() {
  ob::Planner::setup();
  // Motions sampled as OMPL's validators sample them.
  options_.local.resolution_fraction = si_->getStateValidityCheckingResolution();
  if (options_.local.max_displacement > 0) {
    OMPL_WARN(
        "%s: edges are sampled by the scene's max_displacement (%g m), OMPL's motion "
        "validators by the longest valid segment fraction (%g)",
        getName().c_str(), options_.local.max_displacement, options_.local.resolution_fraction);
  }
}

void RoadmapOmplPlanner::clear() {
  ob::Planner::clear();
  planner_.reset();
  last_ = {};
  roadmap_seed_ = 0;
  rounds_ = milestones_ = edges_ = valid_edges_ = 0;
  best_cost_ = std::numeric_limits<double>::infinity();
  free_data_states();
}

std::pair<std::size_t, std::size_t> RoadmapOmplPlanner::checked_edges() const {
  std::size_t valid = 0, invalid = 0;
  if (!planner_) return {0, 0};
  for (const RoadmapEdge& e : planner_->roadmap().edges()) {
    valid += e.state == EdgeState::kValid;
    invalid += e.state == EdgeState::kInvalid;
  }
  return {valid, invalid};
}

ob::PlannerStatus RoadmapOmplPlanner::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  pis_.restart();  // the problem's start and goal at every call (PRM answers from its roadmap)
  const ob::State* start = pis_.nextStart();
  if (start == nullptr) {
    OMPL_ERROR("%s: There are no valid initial states!", getName().c_str());
    return ob::PlannerStatus::INVALID_START;
  }
  const ob::State* goal = pis_.nextGoal(ptc);
  if (goal == nullptr) {
    OMPL_ERROR("%s: Unable to find any valid goal states", getName().c_str());
    return ob::PlannerStatus::INVALID_GOAL;
  }
  if (pis_.haveMoreStartStates() || pis_.haveMoreGoalStates())
    OMPL_WARN("%s: plans from the first valid start to the first valid goal state only",
              getName().c_str());
  const int width = scene_.space.width();
  std::vector<float> a(width), b(width);
  state_to_row(scene_, start, a.data());
  state_to_row(scene_, goal, b.data());

  PlanOptions options = options_;
  options.time_limit_s = std::numeric_limits<double>::infinity();
  options.should_stop = [&ptc] { return ptc.eval(); };
  options.progress = [this](const PlanProgress& p) {
    rounds_ = p.round;
    milestones_ = p.milestones;
    edges_ = p.edges;
    valid_edges_ = p.edges_valid;
  };
  if (!planner_) {
    roadmap_seed_ = options_.seed != 0 ? options_.seed : draw_seed(&rng_);
    options.seed = roadmap_seed_;
    planner_ =
        std::make_unique<RoadmapPlanner>(scene_, checker_, neighbors_.get(), strategy_, options);
  }
  options.seed = roadmap_seed_;
  OMPL_INFORM("%s: Starting planning with %zu states already in datastructure (seed %llu)",
              getName().c_str(), planner_->roadmap().vertex_count(), roadmap_seed_.load());
  const std::size_t states_before = planner_->roadmap().vertex_count();
  const auto [valid_before, invalid_before] = checked_edges();
  planner_->set_options(options);
  last_ = planner_->solve(a.data(), b.data());
  const auto [valid_after, invalid_after] = checked_edges();
  if (ob::MotionValidator* validator = si_->getMotionValidator().get()) {
    MotionCounters::add(validator, valid_after - std::min(valid_after, valid_before),
                        invalid_after - std::min(invalid_after, invalid_before));
  }
  rounds_ = last_.rounds;
  milestones_ = last_.milestones;
  edges_ = last_.edges;
  valid_edges_ = valid_after;
  if (last_.solved) best_cost_ = std::min<double>(best_cost_, last_.length);
  OMPL_INFORM("%s: Created %zu states (%zu rounds, %zu edges; %s)", getName().c_str(),
              last_.milestones - std::min(last_.milestones, states_before), last_.rounds,
              last_.edges, last_.stop_reason.c_str());
  if (last_.stop_reason == "memory limit")
    OMPL_WARN("%s: the roadmap cannot grow further within this machine's memory",
              getName().c_str());
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
