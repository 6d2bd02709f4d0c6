// rostest: the simulator's trajectory controllers, through plain actionlib clients.
#include <cmath>
#include <functional>

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "friend_msgs/MoveJointsAction.h"
#include "imagenets/calling_thread_queue.h"
#include "imagenets/testing/rostest_util.h"

namespace {

using control_msgs::FollowJointTrajectoryGoal;
using control_msgs::FollowJointTrajectoryResult;
using Trajectory = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;
using Move = actionlib::SimpleActionClient<friend_msgs::MoveJointsAction>;
using State = actionlib::SimpleClientGoalState;
constexpr double kDeg = M_PI / 180.0;

const std::vector<std::string> kArm{"arm_joint_1", "arm_joint_2", "arm_joint_3", "arm_joint_4",
                                    "arm_joint_5", "arm_joint_6", "arm_joint_7"};

// The simulator's newest joint state.
class JointStates {
 public:
  // Position of `name` (NaN before the first message or for a joint it does not name).
  double position(const std::string& name) {
    const auto m = latest_.get();
    for (size_t i = 0; m && i < m->name.size(); ++i)
      if (m->name[i] == name) return m->position[i];
    return NAN;
  }
  // Waits for a message stamped after now (so it reflects what the servers just reported).
  bool waitFresh() { return latest_.waitFrom(ros::Time::now() + ros::Duration(0, 1), 30.0) != nullptr; }

 private:
  LatestMessage<sensor_msgs::JointState> latest_{"joint_states"};
};

trajectory_msgs::JointTrajectoryPoint point(double t, std::vector<double> deg, std::vector<double> vel = {}) {
  trajectory_msgs::JointTrajectoryPoint p;
  for (double d : deg) p.positions.push_back(d * kDeg);
  p.velocities = std::move(vel);
  p.time_from_start = ros::Duration(t);
  return p;
}

FollowJointTrajectoryGoal goal(const std::vector<std::string>& joints, std::vector<trajectory_msgs::JointTrajectoryPoint> points) {
  FollowJointTrajectoryGoal g;
  g.trajectory.joint_names = joints;
  g.trajectory.points = std::move(points);
  return g;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class TrajectoryControllers : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(wait([this] { return arm_.isServerConnected() && head_.isServerConnected(); }, 60))
        << "arm_controller/follow_joint_trajectory or head_controller/... missing";
    ASSERT_TRUE(wait([this] { return move_.isServerConnected(); }, 60));
    faults(0.0, "", 0.0);
  }
  void TearDown() override { faults(0.0, "", 0.0); }
  void faults(double abort, const std::string& settle_joint, double settle_error) {
    ros::NodeHandle sim("friend_sim");
    sim.setParam("faults/arm_abort_probability", abort);
    sim.setParam("faults/settle_joint", settle_joint);
    sim.setParam("faults/settle_error", settle_error);  // read by the simulator at each trajectory goal
  }
  bool wait(const std::function<bool()>& done, double seconds) { return queue_.waitUntil(done, seconds); }
  bool done(Trajectory& c, double seconds = 60) {
    return wait([&c] { return c.getState().isDone(); }, seconds);
  }
  void pause(double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    wait([&end] { return ros::WallTime::now() >= end; }, seconds + 1);
  }
  // Sends and waits; the result's error code, or -100 if none came.
  int run(Trajectory& c, const FollowJointTrajectoryGoal& g) {
    c.sendGoal(g);
    if (!done(c)) return -100;
    return c.getResult() ? c.getResult()->error_code : -100;
  }
  void armHome() {
    ASSERT_EQ(run(arm_, goal(kArm, {point(3.0, {0, 0, 0, 0, 0, 0, 0})})), 0) << arm_.getState().getText();
  }

  imagenets::CallingThreadQueue queue_;
  Trajectory arm_{queue_.nodeHandle(), "arm_controller/follow_joint_trajectory", false};
  Trajectory head_{queue_.nodeHandle(), "head_controller/follow_joint_trajectory", false};
  Move move_{queue_.nodeHandle(), "arm/move_joints", false};
  JointStates states_;
};

TEST_F(TrajectoryControllers, WaypointsAreFollowedWithFeedbackAndReportedByJointStates) {
  armHome();
  std::vector<control_msgs::FollowJointTrajectoryFeedbackConstPtr> feedback;
  arm_.sendGoal(goal(kArm, {point(2.0, {10, 20, 0, 30, 0, 0, 0}, {0.1, 0.1, 0, 0.1, 0, 0, 0}),
                            point(4.0, {20, 30, -10, 40, 5, 5, 5}, {0, 0, 0, 0, 0, 0, 0})}),
                Trajectory::SimpleDoneCallback(), Trajectory::SimpleActiveCallback(),
                [&feedback](const control_msgs::FollowJointTrajectoryFeedbackConstPtr& f) { feedback.push_back(f); });
  ASSERT_TRUE(done(arm_));
  EXPECT_EQ(arm_.getState(), State::SUCCEEDED) << arm_.getState().getText();
  EXPECT_EQ(arm_.getResult()->error_code, FollowJointTrajectoryResult::SUCCESSFUL);
  ASSERT_GT(feedback.size(), 3u);
  EXPECT_EQ(feedback.back()->joint_names, kArm);
  EXPECT_EQ(feedback.back()->actual.positions.size(), 7u);
  EXPECT_GE(feedback.back()->desired.time_from_start.toSec(), feedback.front()->desired.time_from_start.toSec());
  ASSERT_TRUE(states_.waitFresh());
  const std::vector<double> end{20, 30, -10, 40, 5, 5, 5};
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(states_.position(kArm[j]), end[j] * kDeg, 1e-9) << kArm[j];
}

TEST_F(TrajectoryControllers, HeadTrajectoryMayStartWithTheCurrentStateAtTimeZero) {
  ASSERT_TRUE(states_.waitFresh());
  const double pan = states_.position("head_pan_joint") / kDeg, tilt = states_.position("head_tilt_joint") / kDeg;
  // Given in the other order than the controller's: names decide.
  EXPECT_EQ(run(head_, goal({"head_tilt_joint", "head_pan_joint"}, {point(0.0, {tilt, pan}), point(2.0, {35, -12})})), 0)
      << head_.getState().getText();
  ASSERT_TRUE(states_.waitFresh());
  EXPECT_NEAR(states_.position("head_pan_joint"), -12 * kDeg, 1e-9);
  EXPECT_NEAR(states_.position("head_tilt_joint"), 35 * kDeg, 1e-9);

  // A time-0 point elsewhere than the joints are cannot be followed.
  EXPECT_EQ(run(head_, goal({"head_pan_joint", "head_tilt_joint"}, {point(0.0, {0, 0}), point(2.0, {0, 0})})),
            FollowJointTrajectoryResult::INVALID_GOAL);
  EXPECT_TRUE(contains(head_.getState().getText(), "a trajectory starts where the joints are")) << head_.getState().getText();
}

TEST_F(TrajectoryControllers, BadGoalsAreRejectedWithTheCodeAndAReason) {
  armHome();
  auto rejected = [this](const FollowJointTrajectoryGoal& g, int code, const std::vector<std::string>& words) {
    EXPECT_EQ(run(arm_, g), code);
    EXPECT_EQ(arm_.getState(), State::REJECTED);
    const std::string text = arm_.getState().getText();
    EXPECT_EQ(arm_.getResult()->error_string, text);
    for (const auto& w : words) EXPECT_TRUE(contains(text, w)) << "'" << w << "' not in: " << text;
  };
  // Not the controller's joints: one missing, one unknown.
  std::vector<std::string> six(kArm.begin(), kArm.end() - 1);
  rejected(goal(six, {point(2.0, {0, 0, 0, 0, 0, 0})}), FollowJointTrajectoryResult::INVALID_JOINTS,
           {"missing 'arm_joint_7'"});
  rejected(goal({"head_pan_joint"}, {point(2.0, {0})}), FollowJointTrajectoryResult::INVALID_JOINTS,
           {"unknown 'head_pan_joint'", "arm_joint_1, arm_joint_2"});
  // Outside the joint limits (joint 4: +-115 deg).
  rejected(goal(kArm, {point(9.0, {0, 0, 0, 150, 0, 0, 0})}), FollowJointTrajectoryResult::INVALID_GOAL,
           {"point 0", "arm_joint_4"});
  // Faster than the joint can go (joint 1: 40 deg/s; 90 deg in 1 s linear).
  rejected(goal(kArm, {point(1.0, {90, 0, 0, 0, 0, 0, 0})}), FollowJointTrajectoryResult::INVALID_GOAL,
           {"joint 'arm_joint_1' would move at", "velocity limit 0.6981 rad/s"});
  // Times must increase.
  rejected(goal(kArm, {point(2.0, {1, 0, 0, 0, 0, 0, 0}), point(2.0, {2, 0, 0, 0, 0, 0, 0})}),
           FollowJointTrajectoryResult::INVALID_GOAL, {"point 1", "does not follow"});
  // A trajectory whose time has passed.
  FollowJointTrajectoryGoal old = goal(kArm, {point(1.0, {1, 0, 0, 0, 0, 0, 0})});
  old.trajectory.header.stamp = ros::Time::now() - ros::Duration(10.0);
  rejected(old, FollowJointTrajectoryResult::OLD_HEADER_TIMESTAMP, {"ended before it arrived"});
}

TEST_F(TrajectoryControllers, AStuckJointViolatesThePathToleranceOfControllersYaml) {
  armHome();
  faults(1.0, "", 0.0);
  EXPECT_EQ(run(arm_, goal(kArm, {point(6.0, {10, 60, 0, 20, 0, 0, 0})})),
            FollowJointTrajectoryResult::PATH_TOLERANCE_VIOLATED);
  EXPECT_EQ(arm_.getState(), State::ABORTED);
  const std::string text = arm_.getResult()->error_string;
  EXPECT_TRUE(contains(text, "joint 'arm_joint_2'")) << text;  // it moves most
  EXPECT_TRUE(contains(text, "(path tolerance 0.1000 rad)")) << text;
}

TEST_F(TrajectoryControllers, ASettleErrorViolatesTheGoalToleranceUnlessTheGoalAllowsIt) {
  armHome();
  faults(0.0, "arm_joint_3", 0.05);
  FollowJointTrajectoryGoal g = goal(kArm, {point(3.0, {0, 10, 10, 10, 0, 0, 0})});
  EXPECT_EQ(run(arm_, g), FollowJointTrajectoryResult::GOAL_TOLERANCE_VIOLATED);
  const std::string text = arm_.getResult()->error_string;
  EXPECT_TRUE(contains(text, "joint 'arm_joint_3' is 0.0500 rad from its goal (goal tolerance 0.0100 rad)")) << text;
  EXPECT_TRUE(contains(text, "goal_time_tolerance 0.500 s")) << text;  // controllers.yaml

  // The goal's own tolerance takes precedence over the controller's.
  control_msgs::JointTolerance loose;
  loose.name = "arm_joint_3";
  loose.position = 0.06;
  g.goal_tolerance.push_back(loose);
  g.trajectory.points[0].positions[1] = 0.0;
  EXPECT_EQ(run(arm_, g), FollowJointTrajectoryResult::SUCCESSFUL) << arm_.getState().getText();
}

TEST_F(TrajectoryControllers, EitherInterfacePreemptsTheOtherAndAnEmptyTrajectoryStops) {
  armHome();
  arm_.sendGoal(goal(kArm, {point(100.0, {60, 0, 0, 0, 0, 0, 0})}));  // 10 s of wall time here
  ASSERT_TRUE(wait([this] { return states_.position("arm_joint_1") > 0.001; }, 60));
  friend_msgs::MoveJointsGoal m;
  m.joint_names = {"arm_joint_1"};
  m.positions = {-5 * kDeg};
  move_.sendGoal(m);
  ASSERT_TRUE(done(arm_));
  EXPECT_EQ(arm_.getState(), State::PREEMPTED);
  ASSERT_TRUE(wait([this] { return move_.getState().isDone(); }, 60));
  EXPECT_EQ(move_.getState(), State::SUCCEEDED);

  // The other way round, and an empty trajectory stops a running one where it is.
  m.positions = {60 * kDeg};
  m.speed_scale = 0.05;
  move_.sendGoal(m);
  ASSERT_TRUE(wait([this] { return states_.position("arm_joint_1") > 0.0; }, 60));
  EXPECT_EQ(run(arm_, goal(kArm, {})), FollowJointTrajectoryResult::SUCCESSFUL);
  ASSERT_TRUE(wait([this] { return move_.getState().isDone(); }, 60));
  EXPECT_EQ(move_.getState(), State::PREEMPTED);
  ASSERT_TRUE(states_.waitFresh());
  const double stopped = states_.position("arm_joint_1");
  EXPECT_LT(stopped, 59 * kDeg);
  pause(0.3);
  ASSERT_TRUE(states_.waitFresh());
  EXPECT_NEAR(states_.position("arm_joint_1"), stopped, 1e-9);

  // Cancel stops too.
  arm_.sendGoal(goal(kArm, {point(100.0, {-60, 0, 0, 0, 0, 0, 0})}));
  ASSERT_TRUE(wait([this, stopped] { return states_.position("arm_joint_1") < stopped - 0.001; }, 60));
  arm_.cancelGoal();
  ASSERT_TRUE(done(arm_));
  EXPECT_EQ(arm_.getState(), State::PREEMPTED);
  EXPECT_TRUE(contains(arm_.getState().getText(), "canceled")) << arm_.getState().getText();
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_trajectory_controllers_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
