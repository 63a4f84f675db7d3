// The OMPL adapters and our planners as OMPL planners refuse what would make them read
// out of bounds or through a null pointer (issue 32): a space information of another layout than
// the scene's (another robot's, a 2-D plane for a 6-DOF piano), none at all, and no checker. Each
// throws std::invalid_argument saying what differs; none crashes.

#include <gtest/gtest.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include <functional>
#include <memory>
#include <string>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/ompl/motion_validator.h"
#include "gplanner/planner/ompl/roadmap_planners.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "test_support.h"

namespace gplanner {
namespace {

namespace ob = ompl::base;
using ompl_adapters::MotionValidator;
using ompl_adapters::StateValidityChecker;

// The message of the std::invalid_argument `make` throws ("" when it throws none).
std::string refusal(const std::function<void()>& make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(AdapterMisuse, AnotherLayoutNoSpaceInformationOrNoCheckerIsRefused) {
  const Scene piano = load_scene(testing::project_root() + "/scenes/piano.yaml");
  const Scene arm = load_scene(testing::project_root() + "/scenes/pr2_reach.yaml");
  CpuChecker checker(piano, 1);
  auto plane = std::make_shared<ob::SE2StateSpace>();
  plane->setBounds(ob::RealVectorBounds(2));
  const auto plane_si = std::make_shared<ob::SpaceInformation>(plane);
  const auto arm_si = std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(arm));
  const auto piano_si =
      std::make_shared<ob::SpaceInformation>(ompl_adapters::make_state_space(piano));
  for (const auto& si : {plane_si, arm_si}) {
    const std::string svc = refusal([&] { StateValidityChecker(si, piano, &checker); });
    EXPECT_NE(svc.find("StateValidityChecker: the space information's state space"),
              std::string::npos)
        << svc;
    EXPECT_NE(svc.find("make_state_space(scene)"), std::string::npos) << svc;
    const std::string mv = refusal([&] { MotionValidator(si, piano, &checker); });
    EXPECT_NE(mv.find("MotionValidator: the space information's state space"), std::string::npos)
        << mv;
    const std::string certified =
        refusal([&] { MotionValidator(si, piano, &checker, EdgeChecks::kCertified); });
    EXPECT_FALSE(certified.empty());
  }
  EXPECT_NE(refusal([&] { StateValidityChecker(nullptr, piano, &checker); }).find("null"),
            std::string::npos);
  EXPECT_NE(
      refusal([&] { StateValidityChecker(piano_si, piano, nullptr); }).find("no collision checker"),
      std::string::npos);
  EXPECT_NE(
      refusal([&] { MotionValidator(piano_si, piano, nullptr); }).find("no collision checker"),
      std::string::npos);
  EXPECT_NE(refusal([&] { MotionValidator(nullptr, piano, &checker); }).find("null"),
            std::string::npos);
  // Our planners as OMPL planners, the same way.
  EXPECT_NE(refusal([&] {
              ompl_adapters::Prm(arm_si, piano, &checker);
            }).find("gplanner PRM: the space information's state space"),
            std::string::npos);
  EXPECT_NE(refusal([&] {
              ompl_adapters::LazyPrm(piano_si, piano, nullptr);
            }).find("no collision checker"),
            std::string::npos);
  // The scene's own layout is taken.
  EXPECT_EQ(refusal([&] { StateValidityChecker(piano_si, piano, &checker); }), "");
  EXPECT_EQ(refusal([&] { MotionValidator(piano_si, piano, &checker); }), "");
}

}  // namespace
}  // namespace gplanner
