// Forward kinematics against poses computed by hand.

#include "gplanner/planner/scene/forward_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "gplanner/planner/scene/configuration_space.h"
#include "gplanner/planner/scene/urdf_loader.h"
#include "test_support.h"

namespace gplanner {
namespace {

constexpr double kPi = 3.14159265358979323846;

// base -(revolute z at (1,0,0))-> l1 -(prismatic x at (0,0,0.5))-> l2
//   -(continuous y at (0.2,0,0))-> l3 -(fixed at (0,0,1), rpy (pi/2,0,0))-> l4
// l1 -(revolute z at (0,1,0), mimics j1: 2 q + 0.1)-> l5
// base -(planar, floating)-> l6, l7 (held at their zero pose)
// Only l4 carries collision geometry (a robot needs some).
const char* kChainUrdf = R"(<?xml version="1.0"?>
<robot name="chain">
  <link name="base"/>
  <link name="l1"/> <link name="l2"/> <link name="l3"/> <link name="l5"/>
  <link name="l4"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="l6"/> <link name="l7"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="1 0 0"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0 0.5"/><axis xyz="2 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j3" type="continuous"><parent link="l2"/><child link="l3"/>
    <origin xyz="0.2 0 0"/><axis xyz="0 1 0"/></joint>
  <joint name="j4" type="fixed"><parent link="l3"/><child link="l4"/>
    <origin xyz="0 0 1" rpy="1.5707963267948966 0 0"/></joint>
  <joint name="j5" type="revolute"><parent link="l1"/><child link="l5"/>
    <origin xyz="0 1 0"/><axis xyz="0 0 1"/><limit lower="-7" upper="7" effort="1" velocity="1"/>
    <mimic joint="j1" multiplier="2" offset="0.1"/></joint>
  <joint name="j6" type="planar"><parent link="base"/><child link="l6"/>
    <origin xyz="0 0 2"/><axis xyz="0 0 1"/></joint>
  <joint name="j7" type="floating"><parent link="base"/><child link="l7"/>
    <origin xyz="0 0 3"/></joint>
</robot>
)";

void expect_pose(const Eigen::Isometry3d& actual, const Eigen::Vector3d& p,
                 const Eigen::Matrix3d& R) {
  EXPECT_TRUE(actual.translation().isApprox(p, 1e-12) || (actual.translation() - p).norm() < 1e-12)
      << "translation " << actual.translation().transpose() << " expected " << p.transpose();
  EXPECT_LT((actual.linear() - R).norm(), 1e-12) << "rotation\n"
                                                 << actual.linear() << "\nexpected\n"
                                                 << R;
}

Eigen::Matrix3d rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

class ForwardKinematics : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string urdf = scratch_.write("chain.urdf", kChainUrdf);
    robot_ = load_urdf(urdf, {}, {"test", 0, "urdf"});
  }
  double position(const std::string& joint, const std::vector<double>& positions) const {
    return positions[robot_.find_joint(joint)];
  }
  testing::ScratchFolder scratch_;
  RobotModel robot_;
};

TEST_F(ForwardKinematics, LoadsJointTypesLimitsAndMimic) {
  ASSERT_EQ(robot_.links.size(), 8u);
  ASSERT_EQ(robot_.joints.size(), 7u);
  EXPECT_EQ(robot_.links[0].name, "base");
  const Joint& j1 = robot_.joints[robot_.find_joint("j1")];
  EXPECT_EQ(j1.type, JointType::kRevolute);
  EXPECT_DOUBLE_EQ(j1.lower, -3);
  EXPECT_DOUBLE_EQ(j1.upper, 3);
  const Joint& j2 = robot_.joints[robot_.find_joint("j2")];
  EXPECT_EQ(j2.type, JointType::kPrismatic);
  EXPECT_TRUE(j2.axis_J.isApprox(Eigen::Vector3d::UnitX()));  // normalised
  const Joint& j3 = robot_.joints[robot_.find_joint("j3")];
  EXPECT_EQ(j3.type, JointType::kContinuous);
  EXPECT_DOUBLE_EQ(j3.upper, kPi);
  EXPECT_EQ(robot_.joints[robot_.find_joint("j4")].type, JointType::kFixed);
  EXPECT_EQ(robot_.joints[robot_.find_joint("j6")].type, JointType::kPlanar);
  EXPECT_EQ(robot_.joints[robot_.find_joint("j7")].type, JointType::kFloating);
  const Joint& j5 = robot_.joints[robot_.find_joint("j5")];
  EXPECT_EQ(j5.mimic_joint, robot_.find_joint("j1"));
  EXPECT_DOUBLE_EQ(j5.mimic_multiplier, 2);
  EXPECT_DOUBLE_EQ(j5.mimic_offset, 0.1);
  // Every link comes after its parent.
  for (std::size_t l = 1; l < robot_.links.size(); ++l) {
    EXPECT_LT(robot_.joints[robot_.links[l].parent_joint].parent_link, static_cast<int>(l));
  }
}

TEST_F(ForwardKinematics, MatchesHandComputedPoses) {
  ConfigurationSpace space;
  space.base = BaseType::kFixed;
  space.fixed_positions.assign(robot_.joints.size(), 0.0);
  for (const char* name : {"j1", "j2", "j3"}) {
    const int j = robot_.find_joint(name);
    space.planned_joints.push_back(j);
    space.lower.push_back(robot_.joints[j].lower);
    space.upper.push_back(robot_.joints[j].upper);
    space.continuous.push_back(robot_.joints[j].type == JointType::kContinuous);
  }
  const float q[3] = {static_cast<float>(kPi / 2), 0.3f, static_cast<float>(kPi)};
  std::vector<double> positions(robot_.joints.size());
  space.joint_positions(robot_, q, positions.data());
  EXPECT_NEAR(position("j5", positions), 2 * q[0] + 0.1, 1e-12);  // the mimic follows j1

  // Use the float values exactly as FK sees them.
  const double q1 = q[0], q2 = q[1], q3 = q[2];
  std::vector<Eigen::Isometry3d> X_WL;
  forward_kinematics(robot_, Eigen::Isometry3d::Identity(), positions.data(), &X_WL);
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), y = Eigen::Vector3d::UnitY();
  const Eigen::Matrix3d R1 = rot(q1, z);
  const auto link = [&](const char* name) { return X_WL[robot_.find_link(name)]; };
  expect_pose(link("base"), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  expect_pose(link("l1"), Eigen::Vector3d(1, 0, 0), R1);
  const Eigen::Vector3d p2 = Eigen::Vector3d(1, 0, 0) + R1 * Eigen::Vector3d(q2, 0, 0.5);
  expect_pose(link("l2"), p2, R1);
  const Eigen::Vector3d p3 = p2 + R1 * Eigen::Vector3d(0.2, 0, 0);
  const Eigen::Matrix3d R3 = R1 * rot(q3, y);
  expect_pose(link("l3"), p3, R3);
  expect_pose(link("l4"), p3 + R3 * Eigen::Vector3d(0, 0, 1),
              R3 * rot(kPi / 2, Eigen::Vector3d::UnitX()));
  expect_pose(link("l5"), Eigen::Vector3d(1, 0, 0) + R1 * Eigen::Vector3d(0, 1, 0),
              R1 * rot(2 * q1 + 0.1, z));
  // With q1 = pi/2 the numbers are simple enough to state outright.
  EXPECT_LT((link("l2").translation() - Eigen::Vector3d(1, 0.3, 0.5)).norm(), 1e-6);
  EXPECT_LT((link("l4").translation() - Eigen::Vector3d(1, 0.5, -0.5)).norm(), 1e-6);
  // Planar and floating URDF joints stay at their zero pose.
  expect_pose(link("l6"), Eigen::Vector3d(0, 0, 2), Eigen::Matrix3d::Identity());
  expect_pose(link("l7"), Eigen::Vector3d(0, 0, 3), Eigen::Matrix3d::Identity());
}

TEST_F(ForwardKinematics, BasePosesMoveTheRoot) {
  std::vector<double> positions(robot_.joints.size(), 0.0);
  ConfigurationSpace floating;
  floating.base = BaseType::kFloating;
  const Eigen::Quaterniond r(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const float q[7] = {1, 2, 3, float(r.w()), float(r.x()), float(r.y()), float(r.z())};
  const Eigen::Isometry3d X_WR = floating.base_pose(q);
  std::vector<Eigen::Isometry3d> X_WL;
  forward_kinematics(robot_, X_WR, positions.data(), &X_WL);
  const Eigen::Matrix3d R = r.toRotationMatrix();
  EXPECT_LT((X_WL[0].translation() - Eigen::Vector3d(1, 2, 3)).norm(), 1e-6);
  EXPECT_LT((X_WL[0].linear() - R).norm(), 1e-6);
  EXPECT_LT((X_WL[robot_.find_link("l1")].translation() -
             (Eigen::Vector3d(1, 2, 3) + R * Eigen::Vector3d(1, 0, 0)))
                .norm(),
            1e-6);

  ConfigurationSpace planar;
  planar.base = BaseType::kPlanar;
  planar.X_SB.translation() = Eigen::Vector3d(0, 0, 0.25);
  const float p[3] = {2, -1, static_cast<float>(kPi / 2)};
  const Eigen::Isometry3d X_WP = planar.base_pose(p);
  EXPECT_LT((X_WP.translation() - Eigen::Vector3d(2, -1, 0.25)).norm(), 1e-6);
  EXPECT_LT((X_WP * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(2, 0, 0.25)).norm(), 1e-6);
}

}  // namespace
}  // namespace gplanner
