// Plans a gplanner scene inside OMPL's own benchmark tool: OMPL's RRTConnect, PRM and
// LazyPRM with gplanner's validity checker and motion validator, beside gplanner's PRM
// and lazy PRM, all on one backend; writes OMPL's benchmark log, which
// `ompl_benchmark_statistics LOG -d DB` turns into an SQLite database (and Planner
// Arena plots).
//
// usage: gplanner_ompl_benchmark SCENE [--backend gpu|cpu|fcl] [--runs N]
//                                [--time-limit SECONDS] [--log FILE] [--seed S]
// --seed: OMPL's random seed (ompl::RNG::setSeed), which seeds every planner's runs, ours
// too; without it OMPL draws one, and runs differ from one start to the next.

#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/tools/benchmark/Benchmark.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "gplanner/planner/ompl/checker_factory.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/roadmap_planners.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: gplanner_ompl_benchmark SCENE [--backend B] [--runs N] "
                 "[--time-limit SECONDS] [--log FILE] [--seed S]\n";
    return 2;
  }
  std::string backend = "gpu", log = "gplanner_benchmark.log";
  unsigned runs = 10;
  double time_limit = 30;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--backend") {
      backend = value;
    } else if (option == "--runs") {
      runs = static_cast<unsigned>(std::atoi(value.c_str()));
    } else if (option == "--time-limit") {
      time_limit = std::atof(value.c_str());
    } else if (option == "--log") {
      log = value;
    } else if (option == "--seed") {
      ompl::RNG::setSeed(std::strtoul(value.c_str(), nullptr, 10));
    } else {
      std::cerr << "unknown option " << option << "\n";
      return 2;
    }
  }
  try {
    const gplanner::Scene scene = gplanner::load_scene(argv[1]);
    // Says through OMPL's console (OMPL_WARN) when the gpu backend runs on the CPU.
    const auto checker = gplanner::ompl_adapters::make_collision_checker(scene, backend);

    // The two lines that give an OMPL setup gplanner's checker: a validity checker and a
    // motion validator on gplanner's backend, in gplanner's state space of the scene.
    og::SimpleSetup setup(gplanner::ompl_adapters::make_state_space(scene));
    const ob::SpaceInformationPtr si = setup.getSpaceInformation();
    setup.setStateValidityChecker(
        std::make_shared<gplanner::ompl_adapters::StateValidityChecker>(si, scene, checker.get()));
    si->setMotionValidator(
        std::make_shared<gplanner::ompl_adapters::MotionValidator>(si, scene, checker.get()));

    ob::ScopedState<> start(si), goal(si);
    gplanner::ompl_adapters::row_to_state(scene, scene.start.data(), start.get());
    gplanner::ompl_adapters::row_to_state(scene, scene.goal.data(), goal.get());
    setup.setStartAndGoalStates(start, goal);

    ompl::tools::Benchmark benchmark(setup, scene.name + " (" + checker->backend() + ")");
    benchmark.addPlanner(std::make_shared<og::RRTConnect>(si));
    benchmark.addPlanner(std::make_shared<og::PRM>(si));
    benchmark.addPlanner(std::make_shared<og::LazyPRM>(si));
    benchmark.addPlanner(std::make_shared<gplanner::ompl_adapters::Prm>(si, scene, checker.get()));
    benchmark.addPlanner(
        std::make_shared<gplanner::ompl_adapters::LazyPrm>(si, scene, checker.get()));
    // Every run starts from an empty roadmap.
    benchmark.setPreRunEvent([](const ob::PlannerPtr& planner) { planner->clear(); });

    ompl::tools::Benchmark::Request request(time_limit, 4096.0, runs);
    request.displayProgress = false;
    benchmark.benchmark(request);
    if (!benchmark.saveResultsToFile(log.c_str())) {
      std::cerr << "gplanner_ompl_benchmark: cannot write " << log << "\n";
      return 1;
    }
    std::cout << "wrote " << log << "\n";
  } catch (const std::exception& e) {
    std::cerr << "gplanner_ompl_benchmark: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
