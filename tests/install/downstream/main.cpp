// Plans a scene with OMPL's RRTConnect on gplanner's checker and with gplanner's lazy
// PRM, through the installed headers and library only, after checking that the library
// loaded is the headers' version.
#include <gplanner/planner/checkers/checker_factory.h>
#include <gplanner/planner/ompl/motion_validator.h>
#include <gplanner/planner/ompl/roadmap_planners.h>
#include <gplanner/planner/ompl/state_space.h>
#include <gplanner/planner/ompl/state_validity_checker.h>
#include <gplanner/planner/scene/scene.h>
#include <gplanner/version.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <iostream>
#include <string>

namespace ob = ompl::base;
namespace og = ompl::geometric;

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  if (std::string(gplanner::version()) != GPLANNER_VERSION_STRING) {
    std::cerr << "headers of gplanner " << GPLANNER_VERSION_STRING << ", library "
              << gplanner::version() << "\n";
    return 1;
  }
  const gplanner::Scene scene = gplanner::load_scene(argv[1]);
  const auto checker = gplanner::make_collision_checker(scene, "cpu");
  for (const bool ours : {false, true}) {
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
    if (ours) {
      setup.setPlanner(
          std::make_shared<gplanner::ompl_adapters::LazyPrm>(si, scene, checker.get()));
    } else {
      setup.setPlanner(std::make_shared<og::RRTConnect>(si));
    }
    if (setup.solve(60.0) != ob::PlannerStatus::EXACT_SOLUTION) {
      std::cerr << (ours ? "gplanner LazyPRM" : "RRTConnect") << ": no path\n";
      return 1;
    }
    std::cout << setup.getPlanner()->getName() << ": path of "
              << setup.getSolutionPath().getStateCount() << " states\n";
  }
  return 0;
}
