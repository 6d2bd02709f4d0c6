// The simulated FRIEND robot as one ROS node: arm and pan-tilt-head action servers, joint_states
// at 50 Hz, force-torque sensor, world model, cameras, and the ground truth (the true robot's
// frames) on ~ground_truth/... for tests and studies only.
//
// Topics/services/actions (relative to the node's namespace, like real drivers):
//   arm/move_joints, head/move_joints     friend_msgs/MoveJoints actions (not with ~move_joints false)
//   arm_controller/follow_joint_trajectory, head_controller/follow_joint_trajectory
//                                         control_msgs/FollowJointTrajectory actions on the same
//                                         joints (as ros_control's joint_trajectory_controller;
//                                         constraints from arm_controller/constraints/..., see
//                                         joint_group_server.h)
//   joint_states                          sensor_msgs/JointState (arm + head, encoder readings)
//   ft_sensor/wrench                      geometry_msgs/WrenchStamped
//   world_model/set, world_model/get      friend_msgs/WorldModelSet, WorldModelGet
//   ~ground_truth/{tcp,marker,left_camera,right_camera,head_base,hand_camera}
//                                         geometry_msgs/TransformStamped (base -> frame, true robot)
//   ~ground_truth/joint_states            exact joint angles (no encoder noise)
//   ~set_true_robot                       friend_msgs/SetTrueRobot: another true robot, live (studies)
// Parameters (private): description, true_error, move_joints (default true), seed, magnitude (factor on the random error's
//   magnitudes; ~seed and ~magnitude are rewritten by ~set_true_robot), time_scale (live), joint_state_rate,
//   encoder_noise (rad), faults/arm_abort_probability, faults/head_abort_probability,
//   faults/settle_joint + faults/settle_error (rad: that joint ends so far from a trajectory's goal),
//   ft_sensor/{payload_mass, payload_com, force_noise, torque_noise}; camera ones in cameras.h.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <random>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "friend_hw_sim/joint_group_server.h"
#include "robot_description/robot_model.h"
#include "friend_msgs/SetTrueRobot.h"
#include "friend_msgs/WorldModelGet.h"
#include "friend_msgs/WorldModelSet.h"

namespace friend_hw_sim {

class CameraSim;

// A snapshot of the simulated robot at one instant.
struct RobotState {
  ros::Time stamp;
  std::vector<double> arm, head;  // true joint angles (encoder values before noise)
  bool arm_moving = false, head_moving = false;
};

class FriendSim {
 public:
  FriendSim(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~FriendSim();

  RobotState state() const;
  const robot_description::RobotModel& nominal() const { return nominal_; }
  // The true robot now (~set_true_robot may replace it at any time: keep the pointer for one
  // consistent view, e.g. one rendered frame).
  std::shared_ptr<const robot_description::RobotModel> truth() const;

 private:
  void tick(const ros::TimerEvent& e);
  bool setObject(friend_msgs::WorldModelSet::Request& req, friend_msgs::WorldModelSet::Response& res);
  bool getObject(friend_msgs::WorldModelGet::Request& req, friend_msgs::WorldModelGet::Response& res);
  bool setTrueRobot(friend_msgs::SetTrueRobot::Request& req, friend_msgs::SetTrueRobot::Response& res);
  void publishGroundTruth(const RobotState& s);
  void publishWrench(const RobotState& s);

  ros::NodeHandle nh_, pnh_;
  robot_description::RobotModel nominal_;
  std::string true_error_file_;
  std::string head_link0_;  // the head chain's first link in TF (the true fixed point's frame)
  mutable std::mutex truth_mutex_;
  std::shared_ptr<const robot_description::RobotModel> truth_;
  double time_scale_ = 1.0;  // ~time_scale, read live (timer thread only)
  std::unique_ptr<JointGroupServer> arm_, head_;
  ros::Publisher joint_states_, truth_joint_states_, wrench_;
  std::map<std::string, ros::Publisher> truth_frames_;
  ros::ServiceServer set_object_, get_object_, set_true_robot_;
  ros::Timer timer_;
  ros::Time last_tick_;
  mutable std::mutex mutex_;
  std::mt19937 rng_;
  std::map<std::string, friend_msgs::WorldModelSet::Request> world_;
  std::unique_ptr<CameraSim> cameras_;
};

}  // namespace friend_hw_sim
