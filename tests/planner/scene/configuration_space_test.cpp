// Sampling, interpolation and bounds of configuration rows.

#include "gplanner/planner/scene/configuration_space.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gplanner {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A floating base with one limited and one continuous joint.
struct Fixture {
  RobotModel robot;
  ConfigurationSpace space;
  Fixture() {
    robot.links.resize(3);
    for (int k = 0; k < 2; ++k) {
      Joint joint;
      joint.name = k == 0 ? "elbow" : "wrist";
      joint.type = k == 0 ? JointType::kRevolute : JointType::kContinuous;
      joint.parent_link = k;
      joint.child_link = k + 1;
      joint.lower = k == 0 ? -1.0 : -kPi;
      joint.upper = k == 0 ? 2.0 : kPi;
      robot.joints.push_back(joint);
      space.planned_joints.push_back(k);
      space.lower.push_back(joint.lower);
      space.upper.push_back(joint.upper);
      space.continuous.push_back(k == 1);
    }
    space.base = BaseType::kFloating;
    space.base_min = Eigen::Vector3d(-1, -2, 0);
    space.base_max = Eigen::Vector3d(1, 2, 3);
    space.fixed_positions.assign(2, 0.0);
  }
};

TEST(ConfigurationSpace, WidthAndDof) {
  Fixture f;
  EXPECT_EQ(f.space.width(), 9);
  EXPECT_EQ(f.space.dof(), 8);
  f.space.base = BaseType::kPlanar;
  EXPECT_EQ(f.space.width(), 5);
  EXPECT_EQ(f.space.dof(), 5);
  f.space.base = BaseType::kFixed;
  EXPECT_EQ(f.space.width(), 2);
}

TEST(ConfigurationSpace, SamplesStayInBoundsAndRotationsAreUniform) {
  Fixture f;
  std::mt19937_64 rng(7);
  std::vector<float> q(f.space.width());
  Eigen::Vector3d mean_axis_component = Eigen::Vector3d::Zero();
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    f.space.sample_uniform(&rng, q.data());
    ASSERT_EQ(f.space.out_of_bounds(f.robot, q.data()), "");
    // The rotated x axis of a uniform rotation is uniform on the sphere: mean ~ 0.
    const Eigen::Quaterniond r(q[3], q[4], q[5], q[6]);
    mean_axis_component += r.normalized() * Eigen::Vector3d::UnitX();
  }
  EXPECT_LT((mean_axis_component / n).norm(), 0.03);
  // Seeded: the same seed gives the same rows.
  std::mt19937_64 a(3), b(3);
  std::vector<float> qa(f.space.width()), qb(f.space.width());
  f.space.sample_uniform(&a, qa.data());
  f.space.sample_uniform(&b, qb.data());
  EXPECT_EQ(qa, qb);
}

TEST(ConfigurationSpace, InterpolatesTheShortWay) {
  Fixture f;
  // Rotations 350 degrees apart about z one way are 10 degrees apart the other way;
  // the second quaternion is also given with the opposite sign (the same rotation).
  const double a_angle = 0.0, b_angle = 350.0 * kPi / 180;
  const Eigen::Quaterniond qa(Eigen::AngleAxisd(a_angle, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond qb(Eigen::AngleAxisd(b_angle, Eigen::Vector3d::UnitZ()));
  const float a[9] = {0,    0,   1, float(qa.w()), float(qa.x()), float(qa.y()), float(qa.z()),
                      0.0f, 3.0f};
  const float b[9] = {1,    0,    1, float(-qb.w()), float(-qb.x()), float(-qb.y()), float(-qb.z()),
                      1.0f, -3.0f};
  float mid[9];
  f.space.interpolate(a, b, 0.5, mid);
  EXPECT_FLOAT_EQ(mid[0], 0.5f);
  const Eigen::Quaterniond qm(mid[3], mid[4], mid[5], mid[6]);
  EXPECT_NEAR(qm.angularDistance(
                  Eigen::Quaterniond(Eigen::AngleAxisd(-5 * kPi / 180, Eigen::Vector3d::UnitZ()))),
              0, 1e-5);
  EXPECT_FLOAT_EQ(mid[7], 0.5f);
  // Continuous joint from 3 to -3 goes through pi, not through 0.
  EXPECT_NEAR(std::abs(mid[8]), kPi, 1e-5);
  f.space.interpolate(a, b, 0.0, mid);
  EXPECT_FLOAT_EQ(mid[8], 3.0f);
}

TEST(ConfigurationSpace, ReportsWhatIsOutOfBounds) {
  Fixture f;
  const float good[9] = {0, 0, 1, 1, 0, 0, 0, 0.5f, 3.1f};
  EXPECT_EQ(f.space.out_of_bounds(f.robot, good), "");
  const float wrap[9] = {0, 0, 1, 1, 0, 0, 0, 0.5f, 10.0f};  // continuous: any finite value
  EXPECT_EQ(f.space.out_of_bounds(f.robot, wrap), "");
  const float bad[9] = {0, 5, 1, 2, 0, 0, 0, 2.5f, 0};
  const std::string why = f.space.out_of_bounds(f.robot, bad);
  EXPECT_NE(why.find("y = 5"), std::string::npos) << why;
  EXPECT_NE(why.find("quaternion"), std::string::npos) << why;
  EXPECT_NE(why.find("elbow"), std::string::npos) << why;
  const float nan[9] = {NAN, 0, 1, 1, 0, 0, 0, 0, 0};
  EXPECT_NE(f.space.out_of_bounds(f.robot, nan).find("not finite"), std::string::npos);
}

TEST(ConfigurationSpace, WrapAngle) {
  EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-3 * kPi / 2), kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(0.25), 0.25, 1e-15);
}

}  // namespace
}  // namespace gplanner
