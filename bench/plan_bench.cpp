// Plan times on one scene: our lazy PRM and PRM (any backend, GPU k-NN with the gpu
// backend) against OMPL's LazyPRM, PRM and RRTConnect as OMPL users run them: one
// planning thread, OMPL's default settings, our FCL backend on that thread as the state
// validity checker, OMPL's DiscreteMotionValidator at the same resolution (the scene's
// edge_resolution of the same largest extent). OMPL's planners can also run with our
// checker as the OMPL plugin gives it (planner name + "@" + backend, e.g.
// ompl-rrtconnect@gpu: our StateValidityChecker and batched MotionValidator on that
// backend, the two lines an OMPL user changes). Every run is a fresh planner with its
// own seed; prints one JSON line per run. An OMPL run that finds a path then simplifies
// it (SimpleSetup::simplifySolution, as OMPL's Benchmark does by default), timed apart
// from the solve; ours reports its stages' times (its shortcutting is part of its time).
//
// usage: gplanner_plan_bench SCENE [--runs N] [--time-limit S] [--planners a,b,...]
//                            [--backend B] [--slow S] [--slow-runs M] [--budget S]
//   planners: ours-lazyprm, ours-prm, ompl-lazyprm, ompl-prm, ompl-rrtconnect (default
//   all), and ompl-lazyprm@B, ompl-prm@B, ompl-rrtconnect@B (B: gpu, cpu or fcl)
//   --backend B: the backend of ours (default gpu)
//   a planner whose first run takes more than --slow seconds (default 30) gets only
//   --slow-runs runs (default 3); --budget S: no new run of a planner starts after it
//   has taken S seconds in all (default: no bound)

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/planning/neighbor_finder.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/planning/roadmap_planner.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/planning/scene_metric.h"

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

struct Run {
  std::string planner, checker;
  int seed = 0;
  bool solved = false;
  double seconds = 0, length = 0;
  double shortcut_seconds = -1;  // ours: of `seconds`, shortening the found path
  // OMPL's: after `seconds`, SimpleSetup::simplifySolution (as OMPL's Benchmark and
  // MoveIt run it after a solve) and the path's length after it.
  double simplify_seconds = -1, simplified_length = 0;
  std::size_t checks = 0;
  std::string details;  // ours: the stage times and counts, a JSON object
};

void print(const gplanner::Scene& scene, const Run& run) {
  std::cout << std::setprecision(6) << "{\"scene\":\"" << scene.name << "\",\"planner\":\""
            << run.planner << "\",\"checker\":\"" << run.checker << "\",\"seed\":" << run.seed
            << ",\"solved\":" << (run.solved ? "true" : "false") << ",\"seconds\":" << run.seconds
            << ",\"length\":" << run.length << ",\"state_checks\":" << run.checks;
  if (run.shortcut_seconds >= 0) std::cout << ",\"shortcut_seconds\":" << run.shortcut_seconds;
  if (run.simplify_seconds >= 0) {
    std::cout << ",\"simplify_seconds\":" << run.simplify_seconds
              << ",\"simplified_length\":" << run.simplified_length;
  }
  if (!run.details.empty()) std::cout << ",\"details\":" << run.details;
  std::cout << "}" << std::endl;
}

// OMPL's planner `name` (ompl-lazyprm, ompl-prm or ompl-rrtconnect). Without `plugin`:
// as OMPL users run it, our FCL backend on the planning thread and OMPL's
// DiscreteMotionValidator. With `plugin`: our validity checker and motion validator on
// that checker, everything else the same.
Run run_ompl(const gplanner::Scene& scene, const std::string& name, double time_limit, int seed,
             gplanner::CollisionChecker* plugin) {
  gplanner::FclChecker fcl(scene, /*threads=*/1);
  gplanner::CollisionChecker* checker_used = plugin ? plugin : &fcl;
  og::SimpleSetup setup(gplanner::ompl_adapters::make_state_space(scene));
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  auto checker =
      std::make_shared<gplanner::ompl_adapters::StateValidityChecker>(si, scene, checker_used);
  setup.setStateValidityChecker(checker);
  std::shared_ptr<gplanner::ompl_adapters::MotionValidator> motions;
  if (plugin) {
    motions = std::make_shared<gplanner::ompl_adapters::MotionValidator>(si, scene, plugin);
    si->setMotionValidator(motions);
  }
  ob::ScopedState<> start(si), goal(si);
  gplanner::ompl_adapters::row_to_state(scene, scene.start.data(), start.get());
  gplanner::ompl_adapters::row_to_state(scene, scene.goal.data(), goal.get());
  setup.setStartAndGoalStates(start, goal);
  if (name == "ompl-lazyprm") {
    setup.setPlanner(std::make_shared<og::LazyPRM>(si));
  } else if (name == "ompl-prm") {
    setup.setPlanner(std::make_shared<og::PRM>(si));
  } else {
    setup.setPlanner(std::make_shared<og::RRTConnect>(si));
  }
  setup.setup();
  Run run{plugin ? name + "@" + plugin->backend() : name,
          plugin ? plugin->backend() + " (OMPL plugin)" : "fcl (1 thread)", seed};
  const ob::PlannerStatus status = setup.solve(time_limit);
  run.seconds = setup.getLastPlanComputationTime();
  run.solved = status == ob::PlannerStatus::EXACT_SOLUTION;
  if (run.solved) {
    run.length = setup.getSolutionPath().length();
    setup.simplifySolution();
    run.simplify_seconds = setup.getLastSimplificationTime();
    run.simplified_length = setup.getSolutionPath().length();
  }
  run.checks = checker->checks();
  return run;
}

Run run_ours(const gplanner::Scene& scene, const std::string& name, double time_limit, int seed,
             gplanner::CollisionChecker* checker, gplanner::NeighborFinder* neighbors) {
  gplanner::PlanOptions options = gplanner::plan_options(scene);
  options.seed = seed;
  options.time_limit_s = time_limit;
  const auto strategy =
      name == "ours-prm" ? gplanner::RoadmapStrategy::kPrm : gplanner::RoadmapStrategy::kLazyPrm;
  gplanner::RoadmapPlanner planner(scene, checker, neighbors, strategy, options);
  const gplanner::PlanResult result = planner.solve(scene.start.data(), scene.goal.data());
  Run run{name, checker->backend() + " (k-NN on the " + neighbors->device() + ")", seed};
  run.solved = result.solved;
  run.seconds = result.times.total;
  run.length = result.length;
  run.checks = result.states_checked + result.samples_checked;
  run.shortcut_seconds = result.times.shortcutting;
  const gplanner::PlanTimes& t = result.times;
  std::ostringstream details;
  details << std::setprecision(6) << "{\"sampling\":" << t.sampling
          << ",\"state_checks\":" << t.state_checks << ",\"knn\":" << t.knn
          << ",\"search\":" << t.search << ",\"edge_checks\":" << t.edge_checks
          << ",\"shortcutting\":" << t.shortcutting << ",\"rounds\":" << result.rounds
          << ",\"milestones\":" << result.milestones << ",\"searches\":" << result.searches
          << ",\"edge_batches\":" << result.edge_batches
          << ",\"length_before_shortcut\":" << result.length_before_shortcut << "}";
  run.details = details.str();
  return run;
}

// "ompl-prm@gpu" -> {"ompl-prm", "gpu"}; "ompl-prm" -> {"ompl-prm", ""}.
std::pair<std::string, std::string> split_planner(const std::string& planner) {
  const std::size_t at = planner.find('@');
  if (at == std::string::npos) return {planner, ""};
  return {planner.substr(0, at), planner.substr(at + 1)};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: gplanner_plan_bench SCENE [--runs N] [--time-limit S] [--planners "
                 "a,b] [--backend B]\n";
    return 2;
  }
  const std::string scene_file = argv[1];
  int runs = 10;
  double time_limit = 60;
  std::string backend = "gpu";
  double slow = 30;
  int slow_runs = 3;
  double budget = 1e30;
  std::vector<std::string> planners = {"ours-lazyprm", "ours-prm", "ompl-lazyprm", "ompl-prm",
                                       "ompl-rrtconnect"};
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--runs") {
      runs = std::atoi(value.c_str());
    } else if (option == "--time-limit") {
      time_limit = std::atof(value.c_str());
    } else if (option == "--slow") {
      slow = std::atof(value.c_str());
    } else if (option == "--budget") {
      budget = std::atof(value.c_str());
    } else if (option == "--slow-runs") {
      slow_runs = std::atoi(value.c_str());
    } else if (option == "--backend") {
      backend = value;
    } else if (option == "--planners") {
      planners.clear();
      std::stringstream list(value);
      for (std::string p; std::getline(list, p, ',');) planners.push_back(p);
    } else {
      std::cerr << "unknown option " << option << "\n";
      return 2;
    }
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(1);
  try {
    const gplanner::Scene scene = gplanner::load_scene(scene_file);
    std::unique_ptr<gplanner::CollisionChecker> checker =
        gplanner::make_collision_checker(scene, backend);
    std::unique_ptr<gplanner::NeighborFinder> neighbors = gplanner::make_neighbor_finder(
        gplanner::make_metric(scene.space, scene.planner), checker->backend());
    std::map<std::string, std::unique_ptr<gplanner::CollisionChecker>> plugins;
    for (const std::string& planner : planners) {
      const auto [base, plugin_backend] = split_planner(planner);
      if ((base != "ours-lazyprm" && base != "ours-prm" && base != "ompl-lazyprm" &&
           base != "ompl-prm" && base != "ompl-rrtconnect") ||
          (!plugin_backend.empty() && base.rfind("ours-", 0) == 0)) {
        std::cerr << "gplanner_plan_bench: unknown planner " << planner << "\n";
        return 2;
      }
      if (!plugin_backend.empty() && !plugins.count(plugin_backend)) {
        std::string notice;
        plugins[plugin_backend] =
            gplanner::make_collision_checker(scene, plugin_backend, {}, &notice);
        if (!notice.empty()) std::cerr << "notice: " << notice << "\n";
      }
    }
    for (const std::string& planner : planners) {
      const auto [base, plugin_backend] = split_planner(planner);
      gplanner::CollisionChecker* plugin =
          plugin_backend.empty() ? nullptr : plugins.at(plugin_backend).get();
      int planned = runs;
      double spent = 0;
      for (int seed = 1; seed <= planned && spent < budget; ++seed) {
        const Run run =
            base.rfind("ours-", 0) == 0
                ? run_ours(scene, base, time_limit, seed, checker.get(), neighbors.get())
                : run_ompl(scene, base, time_limit, seed, plugin);
        print(scene, run);
        spent += run.seconds;
        if (seed == 1 && run.seconds > slow) planned = std::min(planned, slow_runs);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "gplanner_plan_bench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
