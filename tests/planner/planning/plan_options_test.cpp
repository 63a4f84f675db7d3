// The planners' fine checks: at the final check's refinement, except on the CPU backends
// where the path is certified (the fine check is then only the shortcut rounds', and the
// certification that follows is the path's check).

#include "gplanner/planner/planning/plan_options.h"

#include <gtest/gtest.h>

#include "gplanner/planner/checkers/cpu_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "planner/planning/costly_call_checker.h"
#include "test_support.h"

namespace gplanner {
namespace {

TEST(PlanOptions, FineChecksAreCoarserOnlyWhereTheCertificationFollowsOnTheCpu) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/pr2_base_arm.yaml");
  CpuChecker cpu(scene);
  testing::CostlyCallChecker costly(scene, 1000);  // as the GPU's calls
  PlanOptions plan;
  ASSERT_TRUE(plan.certify_path);  // the default
  ASSERT_EQ(plan.final_check_refinement, 10);
  EXPECT_EQ(fine_refinement(plan, cpu), kCertifiedFineRefinement);
  EXPECT_EQ(fine_refinement(plan, costly), 10);
  // Never finer than asked.
  plan.final_check_refinement = 2;
  EXPECT_EQ(fine_refinement(plan, cpu), 2);
  // Certified edges certify the path too.
  plan.final_check_refinement = 10;
  plan.certify_path = false;
  plan.edges = EdgeChecks::kCertified;
  EXPECT_EQ(fine_refinement(plan, cpu), kCertifiedFineRefinement);
  // The fine check is the path's last check: as asked, on every backend.
  plan.edges = EdgeChecks::kSampled;
  EXPECT_EQ(fine_refinement(plan, cpu), 10);
  EXPECT_EQ(fine_refinement(plan, costly), 10);
}

}  // namespace
}  // namespace gplanner
