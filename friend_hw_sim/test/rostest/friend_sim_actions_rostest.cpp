// rostest: the simulated arm and head behave like real actionlib drivers.
#include <cmath>
#include <functional>
#include <mutex>

#include <actionlib/client/simple_action_client.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "friend_msgs/MoveJointsAction.h"
#include "imagenets/calling_thread_queue.h"

namespace {

using Client = actionlib::SimpleActionClient<friend_msgs::MoveJointsAction>;
constexpr double kDeg = M_PI / 180.0;

class JointStates {
 public:
  JointStates() { sub_ = nh_.subscribe("joint_states", 10, &JointStates::cb, this); }
  // Position of `name` in the newest message (NaN if none yet).
  double position(const std::string& name) {
    std::lock_guard<std::mutex> lock(m_);
    for (size_t i = 0; i < last_.name.size(); ++i)
      if (last_.name[i] == name) return last_.position[i];
    return NAN;
  }
  ros::Time stamp() {
    std::lock_guard<std::mutex> lock(m_);
    return last_.header.stamp;
  }
  // Waits for a message published after now (so it reflects what the servers just reported).
  void waitFresh() {
    const ros::Time now = ros::Time::now();
    for (int i = 0; i < 500 && stamp() <= now; ++i) ros::WallDuration(0.01).sleep();
  }

 private:
  void cb(const sensor_msgs::JointState& m) {
    std::lock_guard<std::mutex> lock(m_);
    last_ = m;
  }
  ros::NodeHandle nh_;
  std::mutex m_;
  sensor_msgs::JointState last_;
  // Last, so it is destroyed first: unsubscribing waits for a running cb(), which must still find
  // m_ and last_ alive (joint_states come at 50 Hz, so one is often running when a test ends).
  ros::Subscriber sub_;
};

friend_msgs::MoveJointsGoal goal(std::vector<double> deg, double speed = 1.0) {
  friend_msgs::MoveJointsGoal g;
  for (double d : deg) g.positions.push_back(d * kDeg);
  g.speed_scale = speed;
  return g;
}

std::string armJoint(int i) { return "arm_joint_" + std::to_string(i); }

// The action clients' callbacks run on the test's own thread, inside waitUntil(), never on the
// spinner's (imagenets/calling_thread_queue.h says why).
class FriendSimActions : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(waitUntil([this] { return arm_.isServerConnected(); }, 15)) << "arm/move_joints server missing";
    ASSERT_TRUE(waitUntil([this] { return head_.isServerConnected(); }, 15)) << "head/move_joints server missing";
    ros::NodeHandle("friend_sim").setParam("faults/arm_abort_probability", 0.0);
  }
  bool waitUntil(const std::function<bool()>& done, double seconds) { return clients_.waitUntil(done, seconds); }
  bool waitForResult(Client& client, double seconds) {
    return waitUntil([&client] { return client.getState().isDone(); }, seconds);
  }
  // Lets time pass while the clients' callbacks are handled.
  void pause(double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    waitUntil([&end] { return ros::WallTime::now() >= end; }, seconds + 1);
  }

  imagenets::CallingThreadQueue clients_;
  Client arm_{clients_.nodeHandle(), "arm/move_joints", false};
  Client head_{clients_.nodeHandle(), "head/move_joints", false};
  JointStates states_;
};

TEST_F(FriendSimActions, ArmGoalIsReachedAndReportedByJointStates) {
  const std::vector<double> target{-30, 50, 40, 70, -20, 60, 10};
  arm_.sendGoal(goal(target));
  ASSERT_TRUE(waitForResult(arm_, 20));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << arm_.getState().getText();
  const auto result = arm_.getResult();
  ASSERT_EQ(result->positions.size(), 7u);
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(result->positions[i], target[i] * kDeg, 1e-9) << armJoint(i + 1);
  states_.waitFresh();
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(states_.position(armJoint(i + 1)), target[i] * kDeg, 1e-9) << armJoint(i + 1);
}

TEST_F(FriendSimActions, HeadGoalIsReached) {
  head_.sendGoal(goal({-15, 40}));
  ASSERT_TRUE(waitForResult(head_, 20));
  EXPECT_EQ(head_.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  states_.waitFresh();
  EXPECT_NEAR(states_.position("head_pan_joint"), -15 * kDeg, 1e-9);
  EXPECT_NEAR(states_.position("head_tilt_joint"), 40 * kDeg, 1e-9);
}

TEST_F(FriendSimActions, OutOfLimitGoalIsRejectedWithAReason) {
  arm_.sendGoal(goal({0, 0, 0, 150, 0, 0, 0}));  // joint 4 is limited to +-115 deg
  ASSERT_TRUE(waitForResult(arm_, 10));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::REJECTED);
  const std::string why = arm_.getState().getText();
  EXPECT_NE(why.find("arm_joint_4"), std::string::npos) << why;
  EXPECT_NE(why.find("limits"), std::string::npos) << why;

  friend_msgs::MoveJointsGoal named;
  named.joint_names = {"head_pan_joint", "no_such_joint"};
  named.positions = {0, 0};
  head_.sendGoal(named);
  ASSERT_TRUE(waitForResult(head_, 10));
  EXPECT_EQ(head_.getState(), actionlib::SimpleClientGoalState::REJECTED);
  EXPECT_NE(head_.getState().getText().find("no_such_joint"), std::string::npos) << head_.getState().getText();
}

TEST_F(FriendSimActions, NewGoalPreemptsAndCancelStops) {
  arm_.sendGoal(goal({0, 0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(waitForResult(arm_, 20));
  // A slow, long move; preempt it part way with another client's goal.
  Client other(clients_.nodeHandle(), "arm/move_joints", false);
  ASSERT_TRUE(waitUntil([&other] { return other.isServerConnected(); }, 15));
  arm_.sendGoal(goal({90, 0, 0, 0, 0, 0, 0}, 0.2));
  pause(0.5);
  const double part = states_.position(armJoint(1));
  EXPECT_GT(part, 0.001);
  EXPECT_LT(part, 89 * kDeg);
  other.sendGoal(goal({10, 0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(waitForResult(arm_, 5));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::PREEMPTED);
  ASSERT_TRUE(waitForResult(other, 20));
  EXPECT_EQ(other.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  states_.waitFresh();
  EXPECT_NEAR(states_.position(armJoint(1)), 10 * kDeg, 1e-9);

  // Cancel: the arm stops where it is and stays there.
  arm_.sendGoal(goal({-90, 0, 0, 0, 0, 0, 0}, 0.2));
  pause(0.5);
  arm_.cancelGoal();
  ASSERT_TRUE(waitForResult(arm_, 5));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::PREEMPTED);
  const double stopped = arm_.getResult()->positions[0];
  EXPECT_LT(stopped, 10 * kDeg - 1e-3);
  EXPECT_GT(stopped, -89 * kDeg);
  pause(0.3);  // it must not drift on
  states_.waitFresh();
  EXPECT_NEAR(states_.position(armJoint(1)), stopped, 1e-9);
}

TEST_F(FriendSimActions, FeedbackReportsProgress) {
  std::vector<double> progress;  // filled on this thread, inside waitForResult()
  arm_.sendGoal(goal({20, 20, 0, 30, 0, 0, 0}, 0.2), Client::SimpleDoneCallback(), Client::SimpleActiveCallback(),
                [&progress](const friend_msgs::MoveJointsFeedbackConstPtr& fb) { progress.push_back(fb->progress); });
  ASSERT_TRUE(waitForResult(arm_, 20));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  ASSERT_GT(progress.size(), 3u);
  for (size_t i = 1; i < progress.size(); ++i) EXPECT_GE(progress[i], progress[i - 1]);
  EXPECT_LE(progress.back(), 1.0);
}

TEST_F(FriendSimActions, AbortFaultAbortsPartWay) {
  arm_.sendGoal(goal({0, 0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(waitForResult(arm_, 20));
  ros::NodeHandle("friend_sim").setParam("faults/arm_abort_probability", 1.0);
  pause(0.3);  // the simulator reads the parameter through the cache (updated by the master)
  arm_.sendGoal(goal({60, 0, 0, 0, 0, 0, 0}));
  ASSERT_TRUE(waitForResult(arm_, 20));
  EXPECT_EQ(arm_.getState(), actionlib::SimpleClientGoalState::ABORTED);
  EXPECT_NE(arm_.getState().getText().find("simulated fault"), std::string::npos) << arm_.getState().getText();
  const double reached = arm_.getResult()->positions[0];
  EXPECT_GT(reached, 1 * kDeg);
  EXPECT_LT(reached, 59 * kDeg);
  ros::NodeHandle("friend_sim").setParam("faults/arm_abort_probability", 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_actions_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
