// Classic DH kinematics against textbook results, and the joint-state reader.
#include <cmath>

#include <gtest/gtest.h>

#include "robot_description/joint_state.h"
#include "robot_description/robot_model.h"

using namespace robot_description;

namespace {

KinematicChain chainOf(const std::vector<double>& flat) {
  KinematicChain c;
  c.link_prefix = "link_";
  c.joints = parseDhTable(flat);
  return c;
}

double angleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

}  // namespace

TEST(KinematicChain, PlanarTwoLinkArm) {
  // Two revolute joints about z, links 1.0 and 0.5 along x: the textbook planar arm.
  const KinematicChain arm = chainOf({0, 0, 1.0, 0, 0, 0, 0.5, 0});
  const double q1 = 0.3, q2 = -1.1;
  const Eigen::Isometry3d tip = arm.end({q1, q2});
  const Eigen::Vector3d expected(std::cos(q1) + 0.5 * std::cos(q1 + q2), std::sin(q1) + 0.5 * std::sin(q1 + q2), 0);
  EXPECT_NEAR((tip.translation() - expected).norm(), 0, 1e-12);
  EXPECT_NEAR(angleBetween(tip.linear(), Eigen::AngleAxisd(q1 + q2, Eigen::Vector3d::UnitZ()).toRotationMatrix()), 0,
              1e-9);
}

TEST(KinematicChain, AnthropomorphicArm) {
  // Siciliano et al., "Robotics", 2.9.2: three-link anthropomorphic arm, DH rows
  // (d, theta, a, alpha) = (0, q1, 0, pi/2), (0, q2, a2, 0), (0, q3, a3, 0); its tip position is
  // p = (c1 (a2 c2 + a3 c23), s1 (a2 c2 + a3 c23), a2 s2 + a3 s23).
  const double a2 = 0.4, a3 = 0.3;
  const KinematicChain arm = chainOf({0, 0, 0, M_PI / 2, 0, 0, a2, 0, 0, 0, a3, 0});
  const double q1 = 0.7, q2 = -0.4, q3 = 1.2;
  const auto frames = arm.linkFrames({q1, q2, q3});
  ASSERT_EQ(frames.size(), 4u);  // link 0 (the mount) .. link 3
  const double r = a2 * std::cos(q2) + a3 * std::cos(q2 + q3);
  const Eigen::Vector3d expected(std::cos(q1) * r, std::sin(q1) * r, a2 * std::sin(q2) + a3 * std::sin(q2 + q3));
  EXPECT_NEAR((frames[3].translation() - expected).norm(), 0, 1e-12);
  // Frame 1 is at the base origin, its z axis horizontal: base x rotated by q1 about base z.
  EXPECT_NEAR(frames[1].translation().norm(), 0, 1e-12);
  EXPECT_NEAR((frames[1].linear().col(2) - Eigen::Vector3d(std::sin(q1), -std::cos(q1), 0)).norm(), 0, 1e-12);
  // A theta offset of -q1 in row 1 is the same as joint 1 at 0.
  const KinematicChain offset = chainOf({0, -q1, 0, M_PI / 2, 0, 0, a2, 0, 0, 0, a3, 0});
  EXPECT_NEAR((offset.end({q1, q2, q3}).translation() - arm.end({0, q2, q3}).translation()).norm(), 0, 1e-12);
}

TEST(KinematicChain, PrismaticJointMovesAlongZ) {
  DhJoint slide;
  slide.prismatic = true;
  slide.d = 0.1;
  const Eigen::Isometry3d t = dhTransform(slide, 0.25);
  EXPECT_NEAR((t.translation() - Eigen::Vector3d(0, 0, 0.35)).norm(), 0, 1e-12);
  EXPECT_TRUE(t.linear().isIdentity(1e-12));
}

TEST(KinematicChain, BadTablesAndJointVectorsAreNamed) {
  EXPECT_THROW(parseDhTable({0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(parseDhTable({}), std::invalid_argument);
  try {
    parseDhTable({0, 0, 1, 0, 0, std::nan(""), 1, 0});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 2"), std::string::npos) << e.what();
  }
  const KinematicChain arm = chainOf({0, 0, 1, 0});
  EXPECT_THROW(arm.end({0, 0}), std::invalid_argument);
  try {
    arm.end({std::nan("")});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint_1"), std::string::npos) << e.what();
  }
}

TEST(JointState, PositionsByNameInAnyOrder) {
  sensor_msgs::JointState js;
  js.name = {"tilt", "other", "pan"};
  js.position = {0.2, 9.0, -0.1};
  EXPECT_EQ(jointPositions(js, {"pan", "tilt"}), (std::vector<double>{-0.1, 0.2}));
  try {
    jointPositions(js, {"pan", "roll"});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'roll'"), std::string::npos) << e.what();
  }
  js.position.pop_back();
  EXPECT_THROW(jointPositions(js, {"tilt"}), std::invalid_argument);
}
