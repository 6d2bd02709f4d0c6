// The FollowJointTrajectory block without a controller: the message types are ROS's, the goal it
// builds, its duration from the speed limit, its words for a controller's failure, its checks of
// the input. Against a controller: the rostest trajectory_interop (test/rostest/).
#include <cmath>

#include <boost/make_shared.hpp>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <gtest/gtest.h>

#include "follow_joint_trajectory.h"
#include "imagenets/blocks/block_harness.h"

using imagenets::blocks::BlockHarness;
namespace hardware = imagenets::blocks::hardware;

namespace {

template <class M>
std::string md5() {
  return ros::message_traits::md5sum<M>();
}
template <class M>
std::string type() {
  return ros::message_traits::datatype<M>();
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

// The md5 sums ROS publishes for control_msgs 1.5 (Noetic) in its generated code: a client built
// against the workspace's control_msgs talks to every ROS controller.
TEST(FollowJointTrajectory, MessageTypesAreRosOwn) {
  using namespace control_msgs;
  EXPECT_EQ(md5<FollowJointTrajectoryAction>(), "bc4f9b743838566551c0390c65f1a248");
  EXPECT_EQ(md5<FollowJointTrajectoryActionGoal>(), "cff5c1d533bf2f82dd0138d57f4304bb");
  EXPECT_EQ(md5<FollowJointTrajectoryActionResult>(), "c4fb3b000dc9da4fd99699380efcc5d9");
  EXPECT_EQ(md5<FollowJointTrajectoryActionFeedback>(), "d8920dc4eae9fc107e00999cce4be641");
  EXPECT_EQ(md5<FollowJointTrajectoryGoal>(), "69636787b6ecbde4d61d711979bc7ecb");
  EXPECT_EQ(md5<FollowJointTrajectoryResult>(), "493383b18409bfb604b4e26c676401d2");
  EXPECT_EQ(md5<FollowJointTrajectoryFeedback>(), "10817c60c2486ef6b33e97dcd87f4474");
  EXPECT_EQ(md5<JointTolerance>(), "f544fe9c16cf04547e135dd6063ff5be");
  EXPECT_EQ(md5<JointTrajectoryControllerState>(), "10817c60c2486ef6b33e97dcd87f4474");
  EXPECT_EQ(type<FollowJointTrajectoryActionGoal>(), "control_msgs/FollowJointTrajectoryActionGoal");
  EXPECT_EQ(FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED, -5);
}

TEST(FollowJointTrajectory, DurationKeepsTheFastestJointAtTheSpeedLimit) {
  const auto m = hardware::pointToPoint({"a", "b"}, {0.0, 1.0}, {1.0, 0.5}, 0.5, 0.2);
  EXPECT_DOUBLE_EQ(m.duration, 1.875 * 1.0 / 0.5);  // joint a moves most
  // The quintic's peak speed, numerically, is the limit.
  double peak = 0;
  for (int i = 0; i < 1000; ++i) {
    const double t = m.duration * i / 1000, dt = 1e-6;
    peak = std::max(peak, std::abs(m.position(0, t + dt) - m.position(0, t)) / dt);
  }
  EXPECT_NEAR(peak, 0.5, 1e-3);
  EXPECT_DOUBLE_EQ(m.position(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(m.position(1, m.duration), 0.5);
  EXPECT_DOUBLE_EQ(hardware::pointToPoint({"a"}, {0.0}, {1e-4}, 0.5, 0.2).duration, 0.2);  // min_duration
  EXPECT_THROW(hardware::pointToPoint({"a"}, {0.0}, {1.0}, 0.0, 0.2), std::invalid_argument);
}

TEST(FollowJointTrajectory, GoalIsOneWaypointAtRestWithTolerancesForEveryJoint) {
  const auto m = hardware::pointToPoint({"pan", "tilt"}, {0.0, 0.0}, {0.3, -0.2}, 1.0, 0.1);
  hardware::TrajectoryTolerances tol;
  tol.path = 0.05;
  tol.goal = 0.002;
  tol.goal_time = 0.7;
  const auto g = hardware::trajectoryGoal(m, tol);
  EXPECT_TRUE(g.trajectory.header.stamp.isZero());  // start on receipt
  EXPECT_EQ(g.trajectory.joint_names, (std::vector<std::string>{"pan", "tilt"}));
  ASSERT_EQ(g.trajectory.points.size(), 1u);
  const auto& p = g.trajectory.points[0];
  EXPECT_EQ(p.positions, (std::vector<double>{0.3, -0.2}));
  EXPECT_EQ(p.velocities, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(p.accelerations, (std::vector<double>{0.0, 0.0}));  // quintic in the controller
  EXPECT_NEAR(p.time_from_start.toSec(), 1.875 * 0.3, 1e-9);
  ASSERT_EQ(g.path_tolerance.size(), 2u);
  ASSERT_EQ(g.goal_tolerance.size(), 2u);
  EXPECT_EQ(g.path_tolerance[1].name, "tilt");
  EXPECT_DOUBLE_EQ(g.path_tolerance[1].position, 0.05);
  EXPECT_DOUBLE_EQ(g.goal_tolerance[0].position, 0.002);
  EXPECT_NEAR(g.goal_time_tolerance.toSec(), 0.7, 1e-9);
}

TEST(FollowJointTrajectory, FailureNamesTheJointAndTheTolerance) {
  using control_msgs::FollowJointTrajectoryResult;
  const auto m = hardware::pointToPoint({"j1", "j2", "j3"}, {0, 0, 0}, {0.5, 0.2, -0.1}, 0.5, 0.2);
  hardware::TrajectoryTolerances tol;
  tol.path = 0.05;
  tol.goal = 0.01;
  tol.goal_time = 1.0;
  sensor_msgs::JointState measured;
  measured.name = {"j3", "j1", "j2"};
  measured.position = {-0.1, 0.5, 0.23};  // j2 ended 0.03 rad off
  const std::string goal = hardware::trajectoryFailure(
      "/arm_controller/follow_joint_trajectory", "ABORTED", FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED,
      "goal tolerance violated", m, tol, m.duration + 1.0, &measured);
  EXPECT_TRUE(contains(goal, "'/arm_controller/follow_joint_trajectory' ABORTED")) << goal;
  EXPECT_TRUE(contains(goal, "GOAL_TOLERANCE_VIOLATED (-5)")) << goal;
  EXPECT_TRUE(contains(goal, "joint 'j2' is at 0.2300 rad, 0.0300 rad from its goal 0.2000 rad")) << goal;
  EXPECT_TRUE(contains(goal, "goal tolerance 0.0100 rad (property goal_tolerance)")) << goal;

  // Path: the joint furthest from where the trajectory had it when the controller stopped.
  measured.position = {0.0, 0.0, 0.0};  // nothing moved: j1 lags most half way
  const std::string path = hardware::trajectoryFailure("arm", "ABORTED", FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED,
                                                       "", m, tol, m.duration / 2, &measured);
  EXPECT_TRUE(contains(path, "PATH_TOLERANCE_VIOLATED (-4)")) << path;
  EXPECT_TRUE(contains(path, "joint 'j1'")) << path;
  EXPECT_TRUE(contains(path, "0.2500 rad (path tolerance 0.0500 rad (property path_tolerance))")) << path;

  const std::string joints = hardware::trajectoryFailure("arm", "REJECTED", FollowJointTrajectoryResult::INVALID_JOINTS,
                                                         "unknown 'j3'", m, tol, 0.01, nullptr);
  EXPECT_TRUE(contains(joints, "REJECTED the goal: INVALID_JOINTS (-2): unknown 'j3'")) << joints;
  EXPECT_TRUE(contains(joints, "j1, j2, j3")) << joints;

  const std::string preempted = hardware::trajectoryFailure("arm", "PREEMPTED", 0, "", m, tol, 0.5, nullptr);
  EXPECT_TRUE(contains(preempted, "PREEMPTED the goal after 0.50 s")) << preempted;
  EXPECT_TRUE(contains(preempted, "another goal")) << preempted;
}

TEST(FollowJointTrajectory, BadInputIsNamedBeforeTheRobotIsAsked) {
  auto target = boost::make_shared<sensor_msgs::JointState>();
  target->name = {"arm_joint_1", "arm_joint_2"};
  target->position = {0.1};
  BlockHarness h("imagenets/FollowJointTrajectory");
  EXPECT_TRUE(contains(h.input("configuration", target).runError(), "2 names but 1 positions"));
  target->position = {0.1, NAN};
  EXPECT_TRUE(contains(h.input("configuration", target).runError(), "joint 'arm_joint_2' has no finite position"));
  target->name = {"arm_joint_1", "arm_joint_1"};
  target->position = {0.1, 0.2};
  EXPECT_TRUE(contains(h.input("configuration", target).runError(), "names joint 'arm_joint_1' twice"));
  target->name = {"arm_joint_1", "wrist"};
  h.set("joints", std::string("arm_joint_1, arm_joint_2 arm_joint_3"));
  const std::string unknown = h.input("configuration", target).runError();
  EXPECT_TRUE(contains(unknown, "joint 'wrist', which is not one of the controller's")) << unknown;
  EXPECT_TRUE(contains(unknown, "property joints: arm_joint_1, arm_joint_2, arm_joint_3")) << unknown;
}

// A head without joints (a camera on a stand) moves nowhere: the goal is reached at once, without
// an action server (none runs here); with the controller's joints named, an empty goal is an error.
TEST(FollowJointTrajectory, AGoalWithoutJointsIsReachedAtOnceWithoutAServer) {
  ros::Time::init();
  BlockHarness h("imagenets/FollowJointTrajectory");
  h.set("server_timeout", 0.0);
  h.input("configuration", boost::make_shared<sensor_msgs::JointState>()).run();
  const auto reached = h.output<sensor_msgs::JointState>("reached");
  ASSERT_TRUE(reached);
  EXPECT_TRUE(reached->name.empty());
  EXPECT_TRUE(reached->position.empty());
  EXPECT_FALSE(reached->header.stamp.isZero());
  h.set("joints", std::string("head_pan_joint head_tilt_joint"));
  const std::string error = h.input("configuration", boost::make_shared<sensor_msgs::JointState>()).runError();
  EXPECT_TRUE(contains(error, "names no joint of the controller's (property joints: head_pan_joint, head_tilt_joint)")) << error;
}
