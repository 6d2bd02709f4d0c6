// rostest: the FollowJointTrajectory block against the simulated FRIEND robot's trajectory controllers.
#include <cmath>
#include <cstdio>
#include <mutex>

#include <boost/make_shared.hpp>
#include <control_msgs/FollowJointTrajectoryActionGoal.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/testing/rostest_util.h"

using imagenets::blocks::BlockHarness;

namespace {

constexpr double kDeg = M_PI / 180.0;
const std::vector<std::string> kArm{"arm_joint_1", "arm_joint_2", "arm_joint_3", "arm_joint_4",
                                    "arm_joint_5", "arm_joint_6", "arm_joint_7"};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string failures(const imagenets::RunReport& r) {
  std::string s;
  for (const auto& f : r.failed) s += f + "\n";
  for (const auto& f : r.not_run) s += "not run: " + f + "\n";
  return s;
}

sensor_msgs::JointStatePtr configuration(std::vector<std::string> names, std::vector<double> deg) {
  auto c = boost::make_shared<sensor_msgs::JointState>();
  c->name = std::move(names);
  for (double d : deg) c->position.push_back(d * kDeg);
  return c;
}

double position(const sensor_msgs::JointState& m, const std::string& joint) {
  for (size_t i = 0; i < m.name.size(); ++i)
    if (m.name[i] == joint) return m.position[i];
  return NAN;
}

void faults(double abort, const std::string& settle_joint, double settle_error) {
  ros::NodeHandle sim("friend_sim");
  sim.setParam("faults/arm_abort_probability", abort);
  sim.setParam("faults/settle_joint", settle_joint);
  sim.setParam("faults/settle_error", settle_error);  // read by the simulator at each trajectory goal
}

BlockHarness arm(double max_velocity = 0.6) {
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string("arm_controller/follow_joint_trajectory")).set("max_velocity", max_velocity);
  h.set("server_timeout", 30.0);
  return h;
}

class FriendSimTrajectoryBlocks : public ::testing::Test {
 protected:
  void SetUp() override {
    faults(0.0, "", 0.0);
    ASSERT_TRUE(states_.wait(60)) << "no joint_states from the simulator";
  }
  void TearDown() override { faults(0.0, "", 0.0); }
  LatestMessage<sensor_msgs::JointState> states_{"joint_states"};
  LatestMessage<control_msgs::FollowJointTrajectoryActionGoal> arm_goals_{"arm_controller/follow_joint_trajectory/goal"};
};

TEST_F(FriendSimTrajectoryBlocks, ArmAndHeadMoveThroughTheirTrajectoryControllers) {
  const auto before = states_.waitFrom(ros::Time::now(), 30);
  ASSERT_TRUE(before);
  imagenets::Executor exec(imagenets::Net::build(imagenets::parseNetText(R"(
blocks:
  arm_pose: {type: imagenets/CreateRobotConfiguration,
             properties: {group: arm, angles: [-30, 50, 40, 70, -20, 60, 10],
                          description: $(find friend_description)/config/robot.yaml}}
  head_pose: {type: imagenets/CreateRobotConfiguration,
              properties: {group: head, angles: [-15, 40], description: $(find friend_description)/config/robot.yaml}}
  arm: {type: imagenets/FollowJointTrajectory,
        properties: {action: arm_controller/follow_joint_trajectory, max_velocity: 0.6, server_timeout: 30}}
  head: {type: imagenets/FollowJointTrajectory,
         properties: {action: head_controller/follow_joint_trajectory, max_velocity: 0.9, server_timeout: 30}}
  after: {type: imagenets/ReadJointStates}
links:
  - arm_pose.configuration -> arm.configuration
  - head_pose.configuration -> head.configuration
  - arm.reached -> after.after
)",
                                                                          "<test>", "")),
                           imagenets::ExecutorOptions{2});
  const imagenets::RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << failures(report);
  const std::vector<double> arm_deg{-30, 50, 40, 70, -20, 60, 10};
  const auto reached = exec.output<sensor_msgs::JointState>("arm.reached");
  const auto head = exec.output<sensor_msgs::JointState>("head.reached");
  ASSERT_TRUE(reached && head);
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(position(*reached, kArm[j]), arm_deg[j] * kDeg, 1e-9) << kArm[j];
  EXPECT_NEAR(position(*head, "head_pan_joint"), -15 * kDeg, 1e-9);
  EXPECT_NEAR(position(*head, "head_tilt_joint"), 40 * kDeg, 1e-9);
  const auto now = states_.waitFrom(ros::Time::now(), 30);
  ASSERT_TRUE(now);
  EXPECT_NEAR(position(*now, "arm_joint_4"), 70 * kDeg, 1e-9);
  EXPECT_NEAR(position(*now, "head_tilt_joint"), 40 * kDeg, 1e-9);

  // The goal the arm controller received: one waypoint, its time from the speed limit.
  const auto sent = arm_goals_.get();
  ASSERT_TRUE(sent);
  ASSERT_EQ(sent->goal.trajectory.points.size(), 1u);
  double most = 0;
  for (size_t j = 0; j < 7; ++j) most = std::max(most, std::abs(arm_deg[j] * kDeg - position(*before, kArm[j])));
  const double duration = sent->goal.trajectory.points[0].time_from_start.toSec();
  std::printf("arm trajectory: largest joint motion %.3f rad at max_velocity 0.6 rad/s -> %.3f s\n", most, duration);
  EXPECT_NEAR(duration, 1.875 * most / 0.6, 1e-6);
  EXPECT_EQ(sent->goal.trajectory.joint_names, kArm);
  ASSERT_EQ(sent->goal.goal_tolerance.size(), 7u);
  EXPECT_DOUBLE_EQ(sent->goal.goal_tolerance[0].position, 0.01);  // the block's default
}

TEST_F(FriendSimTrajectoryBlocks, AControllersAbortNamesTheJointAndTheTolerance) {
  ASSERT_EQ(arm().input("configuration", configuration(kArm, {0, 0, 0, 0, 0, 0, 0})).runError(), "");
  faults(1.0, "", 0.0);  // the joint that moves most sticks part way
  std::string error = arm().input("configuration", configuration(kArm, {10, 60, 0, 20, 0, 0, 0})).runError();
  std::printf("stuck joint: %s\n", error.c_str());
  EXPECT_TRUE(contains(error, "'/arm_controller/follow_joint_trajectory' ABORTED the goal: PATH_TOLERANCE_VIOLATED (-4)"))
      << error;
  EXPECT_TRUE(contains(error, "path tolerance violated: joint 'arm_joint_2'")) << error;  // the controller's words
  EXPECT_TRUE(contains(error, "joint 'arm_joint_2' is at")) << error;                     // measured afterwards

  faults(0.0, "", 0.0);
  ASSERT_EQ(arm().input("configuration", configuration(kArm, {0, 0, 0, 0, 0, 0, 0})).runError(), "");
  faults(0.0, "arm_joint_5", 0.04);  // it settles 0.04 rad off its goal
  error = arm().set("goal_tolerance", 0.02).input("configuration", configuration(kArm, {0, 0, 0, 0, 20, 0, 0})).runError();
  std::printf("settle error: %s\n", error.c_str());
  EXPECT_TRUE(contains(error, "GOAL_TOLERANCE_VIOLATED (-5)")) << error;
  EXPECT_TRUE(contains(error, "joint 'arm_joint_5' is 0.0400 rad from its goal (goal tolerance 0.0200 rad)")) << error;
  EXPECT_TRUE(contains(error, "goal tolerance 0.0200 rad (property goal_tolerance)")) << error;
}

TEST_F(FriendSimTrajectoryBlocks, UnknownJointsMissingServersAndTooFastGoalsAreClearErrors) {
  // A joint the controller does not have: the controller's INVALID_JOINTS, with its joints.
  std::string error = arm().input("configuration", configuration({"head_pan_joint", "head_tilt_joint"}, {0, 0})).runError();
  EXPECT_TRUE(contains(error, "REJECTED the goal: INVALID_JOINTS (-2)")) << error;
  EXPECT_TRUE(contains(error, "unknown 'head_pan_joint', 'head_tilt_joint'")) << error;
  EXPECT_TRUE(contains(error, "missing 'arm_joint_1'")) << error;
  // Checked before anything is sent when the block knows the controller's joints.
  error = arm()
              .set("joints", std::string("arm_joint_1 arm_joint_2 arm_joint_3 arm_joint_4 arm_joint_5 arm_joint_6 arm_joint_7"))
              .input("configuration", configuration({"arm_joint_9"}, {10}))
              .runError();
  EXPECT_TRUE(contains(error, "joint 'arm_joint_9', which is not one of the controller's")) << error;
  // No such server: named, with those that exist.
  error = arm().set("action", std::string("torso_controller/follow_joint_trajectory")).set("server_timeout", 1.0)
              .input("configuration", configuration(kArm, {0, 0, 0, 0, 0, 0, 0}))
              .runError();
  EXPECT_TRUE(contains(error, "action server '/torso_controller/follow_joint_trajectory' not available")) << error;
  EXPECT_TRUE(contains(error, "/arm_controller/follow_joint_trajectory, /head_controller/follow_joint_trajectory")) << error;
  // Faster than the joints can go: the controller rejects it, the block says which property.
  error = arm(5.0).input("configuration", configuration(kArm, {80, 0, 0, 0, 0, 0, 0})).runError();
  EXPECT_TRUE(contains(error, "INVALID_GOAL (-1)")) << error;
  EXPECT_TRUE(contains(error, "above its velocity limit")) << error;
  EXPECT_TRUE(contains(error, "property max_velocity")) << error;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_trajectory_blocks_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
