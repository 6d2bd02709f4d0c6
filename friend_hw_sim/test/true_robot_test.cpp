// The simulator's true robot (nominal description + hidden error) and its joint motion.
#include <cmath>

#include <gtest/gtest.h>

#include "friend_hw_sim/joint_trajectory.h"
#include "friend_hw_sim/true_robot.h"
#include "imagenets/package_file.h"

using namespace friend_hw_sim;
using robot_description::loadRobotDescription;
using robot_description::RobotModel;

namespace {
constexpr double kDeg = M_PI / 180.0;

const robot_description::RobotDescription& friendRobot() {
  static const auto d = loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"));
  return d;
}

double angleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}
}  // namespace

TEST(TrueRobot, DefaultTrueErrorIsAboutFifteenMillimetresAndTwoDegrees) {
  const auto nominal = loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"));
  const auto truth = applyTrueError(nominal, loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), nominal));
  const double dt = (truth.head.mount.translation() - nominal.head.mount.translation()).norm();
  const double dr = angleBetween(truth.head.mount.linear(), nominal.head.mount.linear());
  EXPECT_NEAR(dt, 0.015, 0.001);
  EXPECT_NEAR(dr, 2.0 * kDeg, 0.1 * kDeg);
  // The arm's marker moves by millimetres, not centimetres.
  const RobotModel n(nominal), t(truth);
  const double dm = (n.marker(nominal.arm_calibration_pose).translation() - t.marker(nominal.arm_calibration_pose).translation()).norm();
  EXPECT_GT(dm, 1e-4);
  EXPECT_LT(dm, 0.01);
}

TEST(TrueRobot, SeededErrorsAreRepeatableAndOfTheGivenSize) {
  const auto a = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5);
  const auto b = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5);
  const auto c = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 6);
  EXPECT_TRUE(a.head_mount_xyz.isApprox(b.head_mount_xyz));
  EXPECT_FALSE(a.head_mount_xyz.isApprox(c.head_mount_xyz));
  EXPECT_NEAR(a.head_mount_xyz.norm(), 0.015, 1e-12);
  EXPECT_NEAR(a.head_mount_rpy.norm(), 2.0 * kDeg, 1e-12);
  ASSERT_EQ(a.arm_joint_offsets.size(), 7u);
  for (double o : a.arm_joint_offsets) EXPECT_LE(std::abs(o), 0.1 * kDeg);
}

// A random error has one zero offset per joint of the robot it is drawn for, and the same seed
// gives the same mount and marker error whatever the number of joints.
TEST(TrueRobot, RandomJointOffsetsFollowTheRobotsJoints) {
  const auto six_axis = loadRobotDescription(imagenets::packageFile("robot_description", "config/six_axis/robot.yaml"));
  ASSERT_EQ(six_axis.arm.joints.size(), 6u);
  const auto a = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/six_axis_true_error.yaml"), six_axis, 5);
  EXPECT_EQ(a.arm_joint_offsets.size(), 6u);
  EXPECT_EQ(a.head_joint_offsets.size(), 2u);
  const auto f = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5);
  EXPECT_EQ(f.arm_joint_offsets.size(), 7u);
  EXPECT_TRUE(a.head_mount_xyz.normalized().isApprox(f.head_mount_xyz.normalized()));
  // The true robot of that seed is built (applyTrueError checks the counts).
  const RobotModel t(applyTrueError(six_axis, a));
  EXPECT_GT((t.headBase().translation() - RobotModel(six_axis).headBase().translation()).norm(), 1e-3);
}

TEST(TrueRobot, MagnitudeScalesTheRandomErrorAndMustBePositive) {
  const auto a = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5);
  const auto k = loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5, 3.0);
  EXPECT_TRUE(k.head_mount_xyz.isApprox(3.0 * a.head_mount_xyz));  // same direction, three times as far
  EXPECT_NEAR(k.head_mount_rpy.norm(), 6.0 * kDeg, 1e-12);
  EXPECT_NEAR(k.arm_joint_offsets[2], 3.0 * a.arm_joint_offsets[2], 1e-15);
  try {
    loadTrueError(imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"), friendRobot(), 5, -1.0);
    FAIL() << "a negative magnitude was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("true_error.yaml: true_error: the magnitude factor"), std::string::npos)
        << e.what();
  }
}

TEST(TrueRobot, IdentifiableHeadBaseSeesTheArmAsTheNominalModelDoes) {
  // Arm joint 1 and pan zero offsets only: seen from the identifiable head mount, the NOMINAL
  // model's marker sits where the TRUE marker sits seen from the effective (pan-folded) mount, in
  // every arm pose; so no image of the marker can tell the two apart.
  const auto nominal = loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"));
  TrueRobotError e;
  e.arm_joint_offsets = {0.3 * kDeg, 0, 0, 0, 0, 0, 0};
  e.head_joint_offsets = {0.2 * kDeg, 0};
  const RobotModel n(nominal), t(applyTrueError(nominal, e));
  const Eigen::Isometry3d effective = effectiveHeadBase(nominal, e), identifiable = identifiableHeadBase(nominal, e);
  EXPECT_NEAR(angleBetween(effective.linear(), t.headBase().linear()), 0.2 * kDeg, 1e-12);
  EXPECT_NEAR(angleBetween(identifiable.linear(), effective.linear()), 0.3 * kDeg, 1e-12);
  for (auto q : {nominal.arm_calibration_pose, nominal.arm_home}) {
    q[1] += 0.2;
    const Eigen::Isometry3d seen_nominal = identifiable.inverse() * n.marker(q);
    const Eigen::Isometry3d seen_true = effective.inverse() * t.marker(q);
    EXPECT_LT((seen_nominal.translation() - seen_true.translation()).norm(), 1e-12);
    EXPECT_LT(angleBetween(seen_nominal.linear(), seen_true.linear()), 1e-12);
  }
  // Without offsets all three are the true mount.
  const TrueRobotError none;
  EXPECT_TRUE(identifiableHeadBase(nominal, none).isApprox(nominal.head.mount));
}

TEST(JointTrajectory, RespectsVelocityLimitsAndEndsAtTheGoal) {
  const std::vector<double> start{0.0, 1.0}, goal{1.0, 0.5}, vmax{0.5, 2.0};
  const JointTrajectory t(start, goal, vmax, 0.5);
  EXPECT_NEAR(t.duration(), JointTrajectory::kPeakToMean * 1.0 / 0.25, 1e-12);
  double peak = 0;
  std::vector<double> prev = t.positionAt(0);
  const double dt = t.duration() / 2000;
  for (int i = 1; i <= 2000; ++i) {
    const auto q = t.positionAt(i * dt);
    peak = std::max(peak, std::abs(q[0] - prev[0]) / dt);
    prev = q;
  }
  EXPECT_LE(peak, 0.25 + 1e-6);
  EXPECT_GT(peak, 0.24);
  EXPECT_EQ(t.positionAt(t.duration() + 1), goal);
  EXPECT_EQ(t.positionAt(0), start);
  EXPECT_THROW(JointTrajectory(start, goal, vmax, 0.0), std::invalid_argument);
}
