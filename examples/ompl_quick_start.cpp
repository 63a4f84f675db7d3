// The README's "In OMPL code" program, verbatim (a test checks that the README's block
// is contained in this file): OMPL's RRTConnect on a gplanner scene with gplanner's
// checker behind OMPL's state validity checker and motion validator.
//
// usage: gplanner_ompl_quick_start SCENE [gpu|cpu|fcl]

#include <gplanner/planner/ompl/checker_factory.h>
#include <gplanner/planner/ompl/motion_validator.h>
#include <gplanner/planner/ompl/state_space.h>
#include <gplanner/planner/ompl/state_validity_checker.h>
#include <gplanner/planner/scene/scene.h>
#include <ompl/base/ScopedState.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <iostream>
#include <memory>

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace ga = gplanner::ompl_adapters;

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const gplanner::Scene scene = gplanner::load_scene(argv[1]);
  // "gpu", "cpu" or "fcl"; an OMPL warning says when "gpu" runs on the CPU.
  const auto checker = ga::make_collision_checker(scene, argc > 2 ? argv[2] : "gpu");

  og::SimpleSetup setup(ga::make_state_space(scene));
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  setup.setStateValidityChecker(
      std::make_shared<ga::StateValidityChecker>(si, scene, checker.get()));
  si->setMotionValidator(std::make_shared<ga::MotionValidator>(si, scene, checker.get()));

  ob::ScopedState<> start(si), goal(si);
  ga::row_to_state(scene, scene.start.data(), start.get());
  ga::row_to_state(scene, scene.goal.data(), goal.get());
  setup.setStartAndGoalStates(start, goal);
  setup.setPlanner(std::make_shared<og::RRTConnect>(si));
  if (setup.solve(30.0) != ob::PlannerStatus::EXACT_SOLUTION) return 1;
  setup.getSolutionPath().printAsMatrix(std::cout);
  return 0;
}
