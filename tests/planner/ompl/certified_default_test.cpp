// The plugin's motion validator certifies motions by default (issue 32): OMPL's
// RRTConnect through it does not cross a wall thinner than the resolution OMPL samples
// at, where the sampled validator (OMPL's way, still available by name) lets it through.

#include <gtest/gtest.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <memory>
#include <string>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

TEST(CertifiedDefault, RrtConnectDoesNotCrossAWallThinnerThanTheResolution) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  const testing::ScratchFolder folder;
  folder.write("cube.obj", testing::kCubeObj);
  // The cube (0.2 m) from x = -1 to x = 1, a wall 2 cm thick across x = 0: no way through.
  const Scene scene = load_scene(folder.write("wall.yaml", testing::kCubeAndThinWallScene));
  CpuChecker checker(scene, 1);
  for (const bool by_default : {true, false}) {
    SCOPED_TRACE(by_default ? "the default validator" : "the sampled validator");
    og::SimpleSetup setup(ompl_adapters::make_state_space(scene));
    const ob::SpaceInformationPtr si = setup.getSpaceInformation();
    setup.setStateValidityChecker(
        std::make_shared<ompl_adapters::StateValidityChecker>(si, scene, &checker));
    si->setMotionValidator(
        by_default ? std::make_shared<ompl_adapters::MotionValidator>(si, scene, &checker)
                   : std::make_shared<ompl_adapters::MotionValidator>(si, scene, &checker,
                                                                      EdgeChecks::kSampled));
    // Samples half the space apart: far coarser than the wall is thick.
    si->setStateValidityCheckingResolution(0.5);
    ob::ScopedState<> start(si), goal(si);
    ompl_adapters::row_to_state(scene, scene.start.data(), start.get());
    ompl_adapters::row_to_state(scene, scene.goal.data(), goal.get());
    setup.setStartAndGoalStates(start, goal);
    setup.setPlanner(std::make_shared<og::RRTConnect>(si));
    setup.setup();
    // The straight motion through the wall, as RRTConnect asks it.
    EXPECT_EQ(si->checkMotion(start.get(), goal.get()), !by_default);
    const ob::PlannerStatus status = setup.solve(1.0);
    if (by_default) {
      EXPECT_NE(status, ob::PlannerStatus::EXACT_SOLUTION) << "a path through the wall";
    } else {
      EXPECT_EQ(status, ob::PlannerStatus::EXACT_SOLUTION) << "sampling missed the wall";
    }
  }
}

}  // namespace
}  // namespace gplanner
