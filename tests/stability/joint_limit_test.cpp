// Stability: joints at and beyond their limits. The batch call checks a row as given:
// a joint beyond its limit is checked at that value (the geometric verdict, which FCL
// gives too), never clamped or rejected; keeping rows within limits is the caller's
// job, and OMPL's validity checker (planner/ompl/) reports out-of-bounds states
// invalid, as OMPL's own checkers do. Here an arm swings about z within [-1, 1] rad
// between two plates placed so that at either limit the arm's side face lies a known
// gap from a plate's face; beyond the limit it swings into the plate. And the shipped
// articulated scenes with every joint at a limit agree with FCL within the band.

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gplanner/common/gpu_device.h"
#include "gplanner/planner/checkers/checker_comparison.h"
#include "gplanner/planner/checkers/checker_factory.h"
#include "gplanner/planner/checkers/fcl_checker.h"
#include "gplanner/planner/ompl/state_space.h"
#include "gplanner/planner/ompl/state_validity_checker.h"
#include "gplanner/planner/scene/scene.h"
#include "gplanner/planner/scene/scene_collision_model.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// The arm: a 0.8 x 0.1 x 0.1 box from 0.2 to 1 m along x of its joint, about z.
const char* const kSwingUrdf = R"(<robot name="swing">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="0.6 0 0"/><geometry><box size="0.8 0.1 0.1"/></geometry></collision></link>
  <joint name="swing" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
)";

// Two plates like the arm, turned to the arm's limits, their faces `gap` beyond the
// arm's side faces there.
std::string swing_scene(double gap) {
  std::ostringstream out;
  out << std::setprecision(17) << "name: swing\nrobot:\n  urdf: swing.urdf\n"
      << "  planned_joints: [swing]\nobstacles:\n";
  for (const double limit : {1.0, -1.0}) {
    const double side = limit > 0 ? 1 : -1;
    const Eigen::Vector3d centre = Eigen::AngleAxisd(limit, Eigen::Vector3d::UnitZ()) *
                                   Eigen::Vector3d(0.6, side * (0.1 + gap), 0);
    out << "  - box: [0.8, 0.1, 0.1]\n    pose: {xyz: [" << centre.x() << ", " << centre.y()
        << ", 0], quat_wxyz: [" << std::cos(limit / 2) << ", 0, 0, " << std::sin(limit / 2)
        << "]}\n";
  }
  out << "start:\n  joints: {swing: 0}\ngoal:\n  joints: {swing: 0.5}\n";
  return out.str();
}

struct Row {
  float swing;
  const char* what;
  bool clear;  // known: farther than delta from both plates (else: in contact)
};

// Rows with the gap at the limits `gap` (0: touching there).
std::vector<Row> rows(double gap) {
  const bool clear = gap > 0;
  return {
      {0.0f, "mid-range", true},
      {1.0f, "at the upper limit", clear},
      {-1.0f, "at the lower limit", clear},
      {std::nextafter(1.0f, 2.0f), "one float step beyond the upper limit", clear},
      {1.05f, "0.05 rad beyond the upper limit", false},
      {-1.05f, "0.05 rad beyond the lower limit", false},
      {static_cast<float>(1.0 + kTwoPi), "at the upper limit plus a turn", clear},
      {static_cast<float>(1.05 + kTwoPi), "0.05 rad beyond plus a turn", false},
      {3.0f, "3 rad: far beyond, pointing away", true},
  };
}

void expect_geometric_verdicts(const std::string& backend) {
  for (const double gap : {1e-3, 0.0}) {
    testing::ScratchFolder scratch;
    scratch.write("swing.urdf", kSwingUrdf);
    const Scene scene = load_scene(scratch.write("scene.yaml", swing_scene(gap)));
    if (gap > 0) ASSERT_GT(gap, 10 * tolerance_delta(scene));
    auto checker = make_collision_checker(scene, backend);
    ASSERT_EQ(checker->backend(), backend);
    FclChecker fcl(scene, 1);
    for (const Row& row : rows(gap)) {
      const bool hit = checker->in_collision(&row.swing);
      const std::string what = backend + ", gap " + std::to_string(gap) + ", swing " +
                               std::to_string(row.swing) + " (" + row.what + ")";
      EXPECT_EQ(hit, !row.clear) << what;
      // Where the answer is not a touching contact, FCL must give it too: a row beyond
      // the limits is checked where it puts the arm, on every backend alike.
      if (row.clear || std::fabs(std::remainder(row.swing, kTwoPi)) > 1.01)
        EXPECT_EQ(fcl.in_collision(&row.swing), !row.clear) << what << ": fcl";
      else
        std::cout << "fcl at " << what << ": "
                  << (fcl.in_collision(&row.swing) ? "collision" : "free") << " (touching faces)\n";
    }
  }
}

TEST(StabilityJointLimits, BeyondTheLimitsIsCheckedWhereTheRowPutsTheArmCpuAndFcl) {
  expect_geometric_verdicts("cpu");
  expect_geometric_verdicts("fcl");
}

TEST(StabilityJointLimits, GpuBeyondTheLimitsIsCheckedWhereTheRowPutsTheArm) {
  const GpuDevice device = query_gpu_device();
  if (!device.available) GTEST_SKIP() << "no GPU: " << device.reason;
  expect_geometric_verdicts("gpu");
}

// OMPL's validity checker: a state outside the bounds is invalid whatever the
// collision checker says, as OMPL's checkers answer (satisfiesBounds first); so is a
// state holding a NaN (which OMPL's real-vector bounds let through).
TEST(StabilityJointLimits, OmplValidityCheckerRejectsStatesOutsideTheLimits) {
  namespace ob = ompl::base;
  testing::ScratchFolder scratch;
  scratch.write("swing.urdf", kSwingUrdf);
  const Scene scene = load_scene(scratch.write("scene.yaml", swing_scene(1e-3)));
  auto checker = make_collision_checker(scene, "cpu");
  const ob::StateSpacePtr space = ompl_adapters::make_state_space(scene);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  auto validity = std::make_shared<ompl_adapters::StateValidityChecker>(si, scene, checker.get());
  si->setStateValidityChecker(validity);
  si->setup();
  struct Case {
    float swing;
    bool valid;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const Case cases[] = {
      {0.0f, true},   {1.0f, true},
      {-1.0f, true},  {std::nextafter(1.0f, 2.0f), false},
      {1.05f, false}, {static_cast<float>(1.0 + kTwoPi), false},  // free, but out of bounds
      {3.0f, false},                                              // free, but out of bounds
      {nan, false}};
  std::vector<ob::State*> states;
  std::vector<const ob::State*> batch;
  for (const Case& c : cases) {
    states.push_back(space->allocState());
    ompl_adapters::row_to_state(scene, &c.swing, states.back());
    batch.push_back(states.back());
    EXPECT_EQ(validity->isValid(states.back()), c.valid) << "swing " << c.swing;
  }
  std::vector<std::uint8_t> valid;
  validity->areValid(batch, &valid);
  for (std::size_t i = 0; i < batch.size(); ++i)
    EXPECT_EQ(valid[i] != 0, cases[i].valid) << "batch, swing " << cases[i].swing;
  // The free rows beyond the limits are free to the collision checker itself.
  EXPECT_FALSE(checker->in_collision(&cases[5].swing));
  EXPECT_FALSE(checker->in_collision(&cases[6].swing));
  for (ob::State* s : states) space->freeState(s);
}

// Every joint with limits at its lower or upper limit (chosen at random per joint and
// row), the base and continuous joints sampled: cpu against FCL within the band.
void expect_limits_agree(const std::string& file) {
  const Scene scene = load_scene(testing::project_root() + "/scenes/" + file);
  const ConfigurationSpace& space = scene.space;
  const std::size_t n = 1500, w = space.width();
  std::vector<float> q(n * w);
  std::mt19937_64 rng(17);
  std::bernoulli_distribution upper(0.5);
  for (std::size_t i = 0; i < n; ++i) {
    float* row = &q[i * w];
    space.sample_uniform(&rng, row);
    for (std::size_t j = 0; j < space.planned_joints.size(); ++j) {
      if (space.continuous[j]) continue;
      row[space.base_width() + j] =
          static_cast<float>(upper(rng) ? space.upper[j] : space.lower[j]);
    }
  }
  auto cpu = make_collision_checker(scene, "cpu");
  FclChecker fcl(scene);
  std::vector<std::uint8_t> ours(n), theirs(n);
  cpu->check(q.data(), n, ours.data());
  fcl.check(q.data(), n, theirs.data());
  const CheckerComparison c =
      compare_verdicts(q.data(), n, w, ours.data(), theirs.data(), &fcl, tolerance_delta(scene));
  EXPECT_EQ(c.missed_collisions, 0u) << file;
  EXPECT_EQ(c.extra_outside_band, 0u) << file;
  std::size_t hits = 0;
  for (const std::uint8_t v : theirs) hits += v;
  std::cout << file << ", joints at their limits: " << hits << " of " << n << " collide (fcl); "
            << c.disagreements << " disagreements, all within the band\n";
}

TEST(StabilityJointLimits, ShippedScenesAtTheirLimitsAgreeWithFcl) {
  for (const char* file : {"pr2_reach.yaml", "pr2_base_arm.yaml", "humanoid.yaml"})
    expect_limits_agree(file);
}

}  // namespace
}  // namespace gplanner
