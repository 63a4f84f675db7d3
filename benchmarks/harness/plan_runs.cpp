#include "plan_runs.h"

#include <ompl/base/PlannerData.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <chrono>
#include <filesystem>
#include <cmath>
#include <memory>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/output/path_file.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/planning/path_recheck.h"
#include "gplanner/planner/planning/planner_choice.h"
#include "gplanner/planner/planning/scene_metric.h"
#include "gplanner/planner/scene/scene.h"
#include "harness/peak_memory.h"
#include "harness/timed_checks.h"

namespace gplan {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// Seeds OMPL's generator of seeds: every RNG made afterwards (the planner's, its
// samplers') draws its seed from it. OMPL reports an error when seeds were already
// drawn in this process (an earlier run's RNGs), yet reseeds all the same; the message
// is kept quiet.
void seed_ompl(std::uint64_t seed) {
  const ompl::msg::LogLevel level = ompl::msg::getLogLevel();
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(seed));
  ompl::msg::setLogLevel(level);
}

std::vector<float> path_rows(const gplanner::Scene& scene, const og::PathGeometric& path) {
  const std::size_t width = scene.space.width();
  std::vector<float> rows(path.getStateCount() * width);
  for (std::size_t i = 0; i < path.getStateCount(); ++i)
    gplanner::ompl_adapters::state_to_row(scene, path.getState(i), &rows[i * width]);
  return rows;
}

// Where a run's path that failed the re-check is kept (empty: not kept).
struct FailedPaths {
  std::string dir, scene_name, label;
};

void recheck(const gplanner::Scene& scene, const BenchConfig& config,
             const std::vector<float>& path, bool to_goal, const FailedPaths& keep, int run,
             BenchRecord* record) {
  const std::string problem =
      gplanner::path_recheck_problem(scene, path, config.recheck_refinement, to_goal);
  record->path_check = problem.empty() ? "pass" : "fail";
  if (problem.empty()) return;
  record->note = "FCL re-check: " + problem;
  if (config.recheck_refinement > 1) {
    const bool coarse = gplanner::path_recheck_problem(scene, path, 1, to_goal).empty();
    record->note += coarse ? "; free at the planner's own resolution (a collision between its samples)"
                           : "; in collision at the planner's own resolution too";
  }
  if (keep.dir.empty()) return;
  const std::string name = keep.scene_name + "." + keep.label + ".run" + std::to_string(run) + ".yaml";
  try {
    std::filesystem::create_directories(keep.dir);
    gplanner::PlanResult result;
    result.solved = to_goal;
    result.path = path;
    result.length = std::isfinite(record->simplified_length) ? record->simplified_length : record->length;
    gplanner::write_path_file((std::filesystem::path(keep.dir) / name).string(), scene, result,
                              keep.label, record->checker);
    record->note += "; the path: " + (std::filesystem::path(keep.dir).filename() / name).string();
  } catch (const std::exception& e) {
    record->note += std::string("; the path could not be kept: ") + e.what();
  }
}

BenchRecord run_ompl(const gplanner::Scene& scene, const BenchConfig& config,
                     const PlannerChoice& choice, std::uint64_t seed, int run,
                     gplanner::CollisionChecker* checker, const std::function<bool()>& should_stop,
                     const FailedPaths& keep) {
  BenchRecord record;
  record.checker = choice.checker;
  seed_ompl(seed);
  // @fcl: OMPL's own DiscreteMotionValidator; otherwise ours (the plugin), certified as it
  // is by default, or sampled (@gpu-sampled, @cpu-sampled).
  const bool plugin = choice.backend() != "fcl";
  og::SimpleSetup setup(gplanner::ompl_adapters::make_state_space(scene));
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  // Timed: the share of the plan time in collision checks (bench/timed_checks.h).
  const auto clock = std::make_shared<CheckClock>();
  auto validity = std::make_shared<TimedStateValidityChecker>(si, scene, checker, clock);
  setup.setStateValidityChecker(validity);
  if (plugin) {
    si->setMotionValidator(std::make_shared<TimedMotionValidator>(
        si, scene, checker,
        choice.sampled() ? gplanner::EdgeChecks::kSampled : gplanner::EdgeChecks::kCertified,
        clock));
  } else {
    si->setMotionValidator(std::make_shared<TimedDiscreteMotionValidator>(si, clock));
  }
  ob::ScopedState<> start(si), goal(si);
  gplanner::ompl_adapters::row_to_state(scene, scene.start.data(), start.get());
  gplanner::ompl_adapters::row_to_state(scene, scene.goal.data(), goal.get());
  setup.setStartAndGoalStates(start, goal);
  if (choice.planner == "ompl-lazyprm") {
    setup.setPlanner(std::make_shared<og::LazyPRM>(si));
  } else if (choice.planner == "ompl-prm") {
    setup.setPlanner(std::make_shared<og::PRM>(si));
  } else {
    setup.setPlanner(std::make_shared<og::RRTConnect>(si));
  }
  setup.setup();
  const ob::PlannerTerminationCondition stop = ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(config.time_limit_s),
      ob::PlannerTerminationCondition(should_stop));
  const double checked_before = clock->seconds();  // setup's checks (the start, the goal)
  const ob::PlannerStatus status = setup.solve(stop);
  record.time_s = setup.getLastPlanComputationTime();
  record.check_time_s = clock->seconds() - checked_before;
  record.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  record.status = record.solved                                            ? "exact"
                  : status == ob::PlannerStatus::APPROXIMATE_SOLUTION     ? "approximate"
                  : status == ob::PlannerStatus::TIMEOUT                  ? "timeout"
                  : status == ob::PlannerStatus::CRASH                    ? "crash"
                                                                           : "error";
  if (record.status == "error") record.note = "OMPL: " + status.asString();
  if (status == ob::PlannerStatus::EXACT_SOLUTION ||
      status == ob::PlannerStatus::APPROXIMATE_SOLUTION) {
    record.length = setup.getSolutionPath().length();
    if (config.simplify && record.solved) {
      setup.simplifySolution();
      record.simplify_time_s = setup.getLastSimplificationTime();
      record.simplified_length = setup.getSolutionPath().length();
    }
    recheck(scene, config, path_rows(scene, setup.getSolutionPath()), record.solved, keep, run,
            &record);
  }
  ob::PlannerData data(si);
  setup.getPlannerData(data);
  record.graph_states = static_cast<long long>(data.numVertices());
  record.checks = static_cast<long long>(validity->checks());
  return record;
}

BenchRecord run_ours(const gplanner::Scene& scene, const BenchConfig& config,
                     const PlannerChoice& choice, std::uint64_t seed, int run,
                     gplanner::CollisionChecker* checker, gplanner::NeighborFinder* neighbors,
                     const std::function<bool()>& should_stop, const FailedPaths& keep) {
  BenchRecord record;
  record.checker = choice.checker;
  gplanner::PlanOptions options = gplanner::plan_options(scene);
  options.seed = seed;
  options.time_limit_s = config.time_limit_s;
  options.should_stop = should_stop;
  gplanner::PlannerKind kind = gplanner::PlannerKind::kAuto;
  if (!gplanner::parse_planner(choice.planner.substr(5), &kind))  // after "ours-"
    throw std::invalid_argument("no planner of ours is called " + choice.planner);
  gplanner::ChosenPlanner planner(scene, checker, neighbors, kind, /*with_roadmap=*/false, options);
  const gplanner::PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  record.solved = result.solved;
  record.status = result.solved ? "exact" : result.stop_reason == "stopped" ? "error" : "timeout";
  if (!result.solved) record.note = result.stop_reason;
  if (kind == gplanner::PlannerKind::kAuto) {  // which planner answered
    record.note += std::string(record.note.empty() ? "" : "; ") +
                   "auto: " + gplanner::planner_name(planner.used());
  }
  record.time_s = result.times.total;
  record.simplify_time_s = result.times.shortcutting;
  record.sampling_s = result.times.sampling;
  record.state_checks_s = result.times.state_checks;
  record.knn_s = result.times.knn;
  record.search_s = result.times.search;
  record.edge_checks_s = result.times.edge_checks;
  record.rounds = static_cast<long long>(result.rounds);
  record.gpu_calls = static_cast<long long>(result.gpu_calls.total);
  if (result.solved) {
    record.length = result.length_before_shortcut;
    record.simplified_length = result.length;
    recheck(scene, config, result.path, true, keep, run, &record);
  }
  record.checks = static_cast<long long>(result.states_checked + result.samples_checked);
  record.graph_states = static_cast<long long>(result.milestones);
  return record;
}

}  // namespace

void run_planning_group(const gplanner::Scene& scene, const std::string& scene_name, int first_run,
                        const BenchConfig& config, const PlannerChoice& choice, int host_threads,
                        int device, const std::function<void(const BenchRecord&)>& emit,
                        const std::function<bool()>& should_stop,
                        const std::function<void(const std::string&)>& notice,
                        const std::string& failed_paths_dir) {
  const FailedPaths keep{failed_paths_dir, scene_name, choice.label()};
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  // The group's checker, made once and shared by its runs (as a user's program would):
  // OMPL's planners with FCL on the planning thread alone; ours and the plugin on the
  // named backend.
  std::unique_ptr<gplanner::CollisionChecker> checker;
  std::unique_ptr<gplanner::NeighborFinder> neighbors;
  if (!choice.ours() && choice.backend() == "fcl") {
    checker = std::make_unique<gplanner::FclChecker>(scene, /*threads=*/1);
  } else {
    std::string fallback;
    gplanner::CheckerOptions options;
    options.threads = host_threads;
    options.gpu.device = device;
    checker = gplanner::make_collision_checker(scene, choice.backend(), options, &fallback);
    if (checker->backend() != choice.backend())
      throw std::runtime_error(fallback_refusal(choice.label(), fallback));
  }
  if (choice.ours()) {
    std::string knn_notice;
    neighbors =
        gplanner::make_neighbor_finder(gplanner::make_metric(scene.space, scene.planner),
                                       checker->backend(), &knn_notice, checker->gpu_device());
    if (!knn_notice.empty()) notice(knn_notice);
  }
  double spent = 0;
  for (int run = 0; run < config.runs; ++run) {
    if (should_stop()) return;
    if (config.group_budget_s > 0 && spent >= config.group_budget_s) return;
    const std::uint64_t seed = config.seed + static_cast<std::uint64_t>(run);
    reset_peak_memory();
    BenchRecord record;
    try {
      record = choice.ours() ? run_ours(scene, config, choice, seed, first_run + run,
                                        checker.get(), neighbors.get(), should_stop, keep)
                             : run_ompl(scene, config, choice, seed, first_run + run,
                                        checker.get(), should_stop, keep);
    } catch (const std::exception& e) {
      record = BenchRecord{};
      record.status = "error";
      record.note = e.what();
    }
    if (should_stop() && !record.solved) return;  // an interrupted run is no measurement
    record.memory_mb = peak_memory_mb();
    record.experiment = config.name;
    record.scene = scene_name;
    record.planner = choice.planner;
    record.checker = checker->backend() + (choice.sampled() ? "-sampled" : "");
    record.run = first_run + run;
    record.seed = seed;
    record.device = checker->gpu_device();
    spent += std::isfinite(record.time_s) ? record.time_s : config.time_limit_s;
    emit(record);
  }
}

}  // namespace gplan
