// The simulated motor controller of one joint group (the arm, or the pan-tilt head), with two
// action interfaces on the same joints, whichever a client uses:
//
// - friend_msgs/MoveJoints (FRIEND's own): a velocity-limited point-to-point motion; goals outside
//   the joint limits are rejected with a reason; with a fault probability a goal is aborted part way.
// - control_msgs/FollowJointTrajectory (what ros_control's joint_trajectory_controller serves on
//   real arms and heads): the trajectory's waypoints interpolated as that controller does (see
//   SplineTrajectory), checked like it: the goal must name the controller's joints (INVALID_JOINTS
//   otherwise, unless ~allow_partial_joints_goal), waypoints within the joint limits and their
//   velocity limits (INVALID_GOAL), a stamp whose trajectory has not ended (OLD_HEADER_TIMESTAMP);
//   path and goal tolerances from the goal, else from the controller's parameters
//   (<controller>/constraints/<joint>/{trajectory,goal}, <controller>/constraints/goal_time, as
//   joint_trajectory_controller reads them), aborting with PATH_TOLERANCE_VIOLATED /
//   GOAL_TOLERANCE_VIOLATED and an error_string naming the joint, its error and the tolerance; an
//   empty trajectory stops the group. Faults: with the abort probability the joint that moves most
//   sticks part way (so the tolerances catch it); a settle error leaves one joint that far from its
//   goal at the end (a steady-state error only a goal tolerance catches).
//
// Either interface's new goal preempts the running one; cancel stops where the group is.
#pragma once

#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <ros/ros.h>

#include "friend_hw_sim/joint_trajectory.h"
#include "friend_msgs/MoveJointsAction.h"
#include "robot_description/robot_model.h"

namespace friend_hw_sim {

struct JointGroupConfig {
  std::string move_action;        // friend_msgs/MoveJoints server, resolved in the node handle ("" = none)
  std::string trajectory_action;  // control_msgs/FollowJointTrajectory server ("" = none)
  std::string controller;         // the trajectory controller's parameter namespace, e.g. "arm_controller"
  // Fault parameters (read live, full names): the probability in [0, 1] that an accepted goal
  // fails part way; the joint (any group's: only its own group applies it) and error (rad) of a
  // settle error.
  std::string abort_probability_param, settle_joint_param, settle_error_param;
  unsigned seed = 1;
};

class JointGroupServer {
 public:
  using MoveServer = actionlib::ActionServer<friend_msgs::MoveJointsAction>;
  using TrajectoryServer = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;

  JointGroupServer(ros::NodeHandle nh, const JointGroupConfig& config, const robot_description::KinematicChain& chain,
                   const std::vector<double>& start);
  ~JointGroupServer();

  // Advances the motion by sim_dt seconds of simulated time (the node's clock * time_scale).
  void step(double sim_dt);
  std::vector<double> positions() const;
  std::vector<double> velocities() const;
  std::vector<std::string> names() const { return chain_.names(); }
  bool moving() const;
  // The simulated clock's speed-up (trajectory stamps are wall-clock times).
  void setTimeScale(double scale);

 private:
  enum class Mode { idle, move, trajectory };

  void onMoveGoal(MoveServer::GoalHandle gh);
  void onMoveCancel(MoveServer::GoalHandle gh);
  void onTrajectoryGoal(TrajectoryServer::GoalHandle gh);
  void onTrajectoryCancel(TrajectoryServer::GoalHandle gh);
  friend_msgs::MoveJointsResult moveResultLocked(const std::string& message) const;
  // Ends the running goal (if any) as canceled with `why`; the group stops where it is.
  void preemptLocked(const std::string& why);
  // Everything but the joint names checked; "" if the goal is acceptable, else the reason with
  // *code set. Fills the trajectory, tolerances and start offset.
  std::string acceptTrajectoryLocked(const control_msgs::FollowJointTrajectoryGoal& goal,
                                     const std::vector<int>& index, int* code);
  // Its steps: the goal's points as waypoints over all joints (those it leaves out hold still);
  // a joint the spline would move too fast; the tolerances (goal's, else the controller's); the
  // faults the simulator was asked for (a joint sticking, one settling off its goal). The first
  // two return "" or why the goal is refused.
  std::string waypointsLocked(const control_msgs::FollowJointTrajectoryGoal& goal, const std::vector<int>& index,
                              std::vector<Waypoint>* waypoints) const;
  std::string velocityViolation(const SplineTrajectory& spline) const;
  void tolerancesOf(const control_msgs::FollowJointTrajectoryGoal& goal, std::vector<double>* path,
                    std::vector<double>* at_goal) const;
  void planFaultsLocked();
  void stepTrajectoryLocked(double sim_dt);
  void endTrajectoryLocked(int code, const std::string& text);
  double param(const std::string& name, double fallback) const;

  ros::NodeHandle nh_;
  JointGroupConfig config_;
  std::string move_action_, trajectory_action_;  // resolved, for messages
  robot_description::KinematicChain chain_;
  mutable std::mutex mutex_;
  std::vector<double> q_, qd_;
  Mode mode_ = Mode::idle;
  std::mt19937 rng_;

  // MoveJoints motion.
  MoveServer::GoalHandle move_goal_;
  JointTrajectory move_trajectory_;
  double abort_at_ = 2.0;  // progress at which a faulty goal is aborted (> 1: never)

  // FollowJointTrajectory motion.
  TrajectoryServer::GoalHandle trajectory_goal_;
  SplineTrajectory spline_;
  std::vector<double> path_tolerance_, goal_tolerance_;  // per joint; <= 0: none
  double goal_time_ = 0;                                  // s after the end; 0: at the end
  int stuck_joint_ = -1;                                  // fault: this joint sticks at stuck_at_ progress
  double stuck_at_ = 2.0, stuck_position_ = 0;
  bool stuck_ = false;
  int settle_joint_ = -1;  // fault: this joint ends settle_error_ from its goal
  double settle_error_ = 0;

  double time_scale_ = 1.0;
  double t_ = 0;  // simulated seconds since the motion started (a trajectory may start later: < 0)
  std::unique_ptr<MoveServer> move_server_;
  std::unique_ptr<TrajectoryServer> trajectory_server_;
};

}  // namespace friend_hw_sim
