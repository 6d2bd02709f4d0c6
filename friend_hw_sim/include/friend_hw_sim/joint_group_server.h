// The simulated motor controller of one joint group (the arm, or the pan-tilt head): an actionlib
// server for friend_msgs/MoveJoints that moves the group along a velocity-limited trajectory in
// simulated time. Goals outside the joint limits are rejected with a reason; a new goal preempts
// the running one; cancel stops where the group is; with a fault probability a goal is aborted
// part way, like a real controller that trips.
#pragma once

#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include <actionlib/server/action_server.h>
#include <ros/ros.h>

#include "friend_hw_sim/joint_trajectory.h"
#include "robot_description/robot_model.h"
#include "friend_msgs/MoveJointsAction.h"

namespace friend_hw_sim {

class JointGroupServer {
 public:
  using Server = actionlib::ActionServer<friend_msgs::MoveJointsAction>;
  using GoalHandle = Server::GoalHandle;

  // `action_name` is resolved in nh; `fault_param` is a parameter (read live) holding the
  // probability in [0, 1] that an accepted goal is aborted part way.
  JointGroupServer(ros::NodeHandle nh, const std::string& action_name, const robot_description::KinematicChain& chain,
                   const std::vector<double>& start, std::string fault_param, unsigned seed);
  ~JointGroupServer();

  // Advances the motion by sim_dt seconds of simulated time (the node's clock * time_scale).
  void step(double sim_dt);
  std::vector<double> positions() const;
  std::vector<double> velocities() const;
  std::vector<std::string> names() const { return chain_.names(); }
  bool moving() const;

 private:
  void onGoal(GoalHandle gh);
  void onCancel(GoalHandle gh);
  friend_msgs::MoveJointsResult resultLocked(const std::string& message) const;

  ros::NodeHandle nh_;
  std::string action_name_;
  robot_description::KinematicChain chain_;
  std::string fault_param_;
  mutable std::mutex mutex_;
  std::vector<double> q_, qd_;
  bool active_ = false;
  GoalHandle goal_;
  JointTrajectory trajectory_;
  double t_ = 0;
  double abort_at_ = 2.0;  // progress at which a faulty goal is aborted (> 1: never)
  std::mt19937 rng_;
  std::unique_ptr<Server> server_;
};

}  // namespace friend_hw_sim
