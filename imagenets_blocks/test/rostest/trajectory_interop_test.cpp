// rostest: the FollowJointTrajectory block against a Python controller (trajectory_controller.py).
#include <atomic>
#include <cmath>
#include <thread>

#include <actionlib/client/simple_action_client.h>
#include <boost/make_shared.hpp>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/calling_thread_queue.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/port_type.h"
#include "imagenets/testing/rostest_util.h"

using imagenets::blocks::BlockHarness;

namespace {

const char* kAction = "/arm_controller/follow_joint_trajectory";

sensor_msgs::JointStatePtr configuration(std::vector<std::string> names, std::vector<double> positions) {
  auto c = boost::make_shared<sensor_msgs::JointState>();
  c->name = std::move(names);
  c->position = std::move(positions);
  return c;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

double position(LatestMessage<sensor_msgs::JointState>& states, const std::string& joint) {
  const auto m = states.get();
  if (!m) return NAN;
  for (size_t i = 0; i < m->name.size(); ++i)
    if (m->name[i] == joint) return m->position[i];
  return NAN;
}

class TrajectoryInterop : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::param::set("/arm/settle_joint", "");
    ros::param::set("/arm/settle_error", 0.0);
    ASSERT_TRUE(waitFor([this] { return states_.get() != nullptr; }, 60)) << "the Python controller publishes nothing";
    ros::param::del("/arm/last_goal");
  }
  // Moves j1, j2 home (0, 0) so each test starts from rest at a known place.
  void home() {
    BlockHarness h("imagenets/FollowJointTrajectory");
    h.set("action", std::string(kAction)).set("max_velocity", 4.0).set("server_timeout", 30.0);
    ASSERT_EQ(h.input("configuration", configuration({"j1", "j2"}, {0, 0})).runError(), "");
  }
  LatestMessage<sensor_msgs::JointState> states_{"joint_states"};
};

TEST_F(TrajectoryInterop, ThePythonControllerFollowsTheGoalOfTheCppBlock) {
  home();
  // The two sides computed the action goal's md5 sum each from their own generated code.
  std::string python_md5;
  ASSERT_TRUE(ros::param::get("/arm/md5sum", python_md5));
  EXPECT_EQ(python_md5, ros::message_traits::md5sum<control_msgs::FollowJointTrajectoryActionGoal>());

  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string(kAction)).set("max_velocity", 1.0).set("goal_tolerance", 0.002);
  h.set("path_tolerance", 0.05).set("goal_time_tolerance", 0.4);
  h.input("configuration", configuration({"j2", "j1"}, {-0.2, 0.4}));
  ASSERT_EQ(h.runError(), "");
  const auto reached = h.output<sensor_msgs::JointState>("reached");
  ASSERT_TRUE(reached);
  EXPECT_EQ(reached->name, (std::vector<std::string>{"j2", "j1"}));  // the goal's order: the input's
  EXPECT_NEAR(reached->position[0], -0.2, 1e-9);
  EXPECT_NEAR(reached->position[1], 0.4, 1e-9);

  // What arrived, as the Python side decoded it.
  XmlRpc::XmlRpcValue goal;
  ASSERT_TRUE(ros::param::get("/arm/last_goal", goal));
  EXPECT_NEAR(static_cast<double>(goal["duration"]), 1.875 * 0.4 / 1.0, 1e-9);  // j1 moves most
  EXPECT_EQ(static_cast<int>(goal["points"]), 1);
  EXPECT_EQ(static_cast<double>(goal["stamp"]), 0.0);
  EXPECT_EQ(static_cast<double>(goal["velocities"][1]), 0.0);
  EXPECT_EQ(static_cast<double>(goal["accelerations"][0]), 0.0);
  EXPECT_DOUBLE_EQ(static_cast<double>(goal["path_tolerance"][0]), 0.05);
  EXPECT_DOUBLE_EQ(static_cast<double>(goal["goal_tolerance"][1]), 0.002);
  EXPECT_NEAR(static_cast<double>(goal["goal_time_tolerance"]), 0.4, 1e-9);
}

TEST_F(TrajectoryInterop, JointsTheInputLeavesOutKeepTheirPosition) {
  home();
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string(kAction)).set("max_velocity", 2.0).set("joints", std::string("j1, j2"));
  ASSERT_EQ(h.input("configuration", configuration({"j1"}, {0.3})).runError(), "");
  ASSERT_EQ(h.input("configuration", configuration({"j2"}, {0.1})).runError(), "");
  const auto reached = h.output<sensor_msgs::JointState>("reached");
  ASSERT_TRUE(reached);
  EXPECT_EQ(reached->name, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_NEAR(reached->position[0], 0.3, 1e-9);  // kept
  EXPECT_NEAR(reached->position[1], 0.1, 1e-9);
}

TEST_F(TrajectoryInterop, ARejectionNamesTheJointsTheControllerWanted) {
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string(kAction));
  const std::string error = h.input("configuration", configuration({"j1"}, {0.1})).runError();
  EXPECT_TRUE(contains(error, "REJECTED the goal: INVALID_JOINTS (-2)")) << error;
  EXPECT_TRUE(contains(error, "missing ['j2']")) << error;  // the controller's own words
  EXPECT_TRUE(contains(error, "the goal named j1")) << error;

  // A joint joint_states does not carry fails before any goal is sent.
  const std::string unknown = h.input("configuration", configuration({"j1", "elbow"}, {0.1, 0.2})).runError();
  EXPECT_TRUE(contains(unknown, "no position of joint 'elbow' on '/joint_states'")) << unknown;
  EXPECT_TRUE(contains(unknown, "its messages name j1, j2")) << unknown;
}

TEST_F(TrajectoryInterop, AGoalToleranceAbortNamesTheJointAndTheTolerance) {
  home();
  ros::param::set("/arm/settle_joint", "j2");
  ros::param::set("/arm/settle_error", 0.05);
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string(kAction)).set("max_velocity", 2.0).set("goal_tolerance", 0.01);
  const std::string error = h.input("configuration", configuration({"j1", "j2"}, {0.2, 0.2})).runError();
  EXPECT_TRUE(contains(error, "ABORTED the goal: GOAL_TOLERANCE_VIOLATED (-5)")) << error;
  EXPECT_TRUE(contains(error, "joint 'j2' ended 0.0500 rad from its goal")) << error;        // the controller's
  EXPECT_TRUE(contains(error, "joint 'j2' is at 0.2500 rad, 0.0500 rad from its goal")) << error;  // measured
  EXPECT_TRUE(contains(error, "goal tolerance 0.0100 rad (property goal_tolerance)")) << error;
}

TEST_F(TrajectoryInterop, AnotherClientsGoalPreemptsTheBlocksGoal) {
  home();
  std::string error = "(not run)";
  std::thread slow([&error] {
    BlockHarness h("imagenets/FollowJointTrajectory");
    h.set("action", std::string(kAction)).set("max_velocity", 0.05);  // 1 rad at 0.05 rad/s: 37 s
    error = h.input("configuration", configuration({"j1", "j2"}, {1.0, 0.0})).runError();
  });
  ASSERT_TRUE(waitFor([this] { return position(states_, "j1") > 0.001; }, 60)) << "the slow motion did not start";
  imagenets::CallingThreadQueue queue;
  actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction> other(queue.nodeHandle(), kAction, false);
  ASSERT_TRUE(queue.waitUntil([&] { return other.isServerConnected(); }, 30));
  control_msgs::FollowJointTrajectoryGoal goal;
  goal.trajectory.joint_names = {"j1", "j2"};
  goal.trajectory.points.resize(1);
  goal.trajectory.points[0].positions = {0.0, 0.0};
  goal.trajectory.points[0].time_from_start = ros::Duration(0.5);
  other.sendGoal(goal);
  slow.join();
  EXPECT_TRUE(contains(error, "PREEMPTED the goal after")) << error;
  EXPECT_TRUE(contains(error, "another goal reached the controller")) << error;
  ASSERT_TRUE(queue.waitUntil([&] { return other.getState().isDone(); }, 30));
  EXPECT_EQ(other.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
}

TEST_F(TrajectoryInterop, CancellingTheRunCancelsTheGoal) {
  home();
  imagenets::Executor exec(imagenets::Net::build(imagenets::parseNetText(R"(
blocks:
  move: {type: imagenets/FollowJointTrajectory,
         properties: {action: /arm_controller/follow_joint_trajectory, max_velocity: 0.05}}
)",
                                                                          "<test>", "")),
                           imagenets::ExecutorOptions{2});
  exec.setInput("move.configuration", imagenets::PortType::of<sensor_msgs::JointState>().wrap(
                                          boost::shared_ptr<const sensor_msgs::JointState>(
                                              configuration({"j1", "j2"}, {1.0, 0.0}))));
  imagenets::RunReport report;
  std::thread run([&] { report = exec.run(); });
  ASSERT_TRUE(waitFor([this] { return position(states_, "j1") > 0.001; }, 60)) << "the motion did not start";
  exec.cancel();
  run.join();
  EXPECT_TRUE(report.cancelled);
  EXPECT_TRUE(report.failed.empty()) << report.failed[0];
  // The controller stopped the joints short of the goal, and they stay there.
  ASSERT_TRUE(states_.waitFrom(ros::Time::now(), 30));
  const double stopped = position(states_, "j1");
  EXPECT_LT(stopped, 0.9);
  ASSERT_TRUE(states_.waitFrom(ros::Time::now() + ros::Duration(0.3), 30));
  EXPECT_NEAR(position(states_, "j1"), stopped, 1e-9);
}

TEST_F(TrajectoryInterop, AMissingServerIsNamedWithTheServersThatExist) {
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("action", std::string("/head_controller/follow_joint_trajectory")).set("server_timeout", 1.0);
  const std::string error = h.input("configuration", configuration({"j1", "j2"}, {0, 0})).runError();
  EXPECT_TRUE(contains(error, "action server '/head_controller/follow_joint_trajectory' not available after")) << error;
  EXPECT_TRUE(contains(error, "FollowJointTrajectory servers the master knows: /arm_controller/follow_joint_trajectory"))
      << error;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "trajectory_interop_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
