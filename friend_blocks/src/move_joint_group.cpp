#include "move_joint_group.h"

#include "friend_msgs/MoveJointsAction.h"
#include "imagenets/blocks/action_clients.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {
namespace {

using hardware::ensureRosNode;

// Sends a friend_msgs/MoveJoints goal and waits for the result; returns the reached positions.
// Throws BlockError naming the action when the server is missing, rejects, aborts or times out.
sensor_msgs::JointStatePtr moveJoints(const std::string& action_name, const sensor_msgs::JointState& target,
                                      double speed_scale, double server_timeout, double motion_timeout) {
  ensureRosNode();
  hardware::ActionClientLease<friend_msgs::MoveJointsAction> lease(action_name);
  const std::string& action = lease.action();
  auto& client = lease.client();
  if (!lease.waitUntil([&client] { return client.isServerConnected(); }, server_timeout)) {
    throw BlockError("action server '" + action + "' not available after " + std::to_string(server_timeout) +
                     " s (property server_timeout)");
  }
  friend_msgs::MoveJointsGoal goal;
  goal.joint_names = target.name;
  goal.positions = target.position;
  goal.speed_scale = speed_scale;
  client.sendGoal(goal);
  bool lost = false;  // the server went away mid-motion (the robot's driver stopped): fail at once
  const bool finished = lease.waitUntil(
      [&] {
        lost = !client.getState().isDone() && !client.isServerConnected();
        return lost || client.getState().isDone();
      },
      motion_timeout);
  if (lost) {
    client.cancelGoal();
    lease.reset();
    throw BlockError("action server '" + action + "' lost during the motion (the robot's driver / friend_sim stopped?)");
  }
  if (!finished) {
    client.cancelGoal();
    throw BlockError("'" + action + "' did not finish within " + std::to_string(motion_timeout) +
                     " s (property motion_timeout); goal canceled");
  }
  const auto state = client.getState();
  if (state != actionlib::SimpleClientGoalState::SUCCEEDED) {
    throw BlockError("'" + action + "' " + state.toString() + ": " + state.getText());
  }
  auto reached = boost::make_shared<sensor_msgs::JointState>();
  reached->header.stamp = ros::Time::now();
  reached->name = client.getResult()->joint_names;
  reached->position = client.getResult()->positions;
  return reached;
}

}  // namespace

MoveJointGroup::MoveJointGroup(const std::string& target_doc, const std::string& default_action,
                               const std::string& action_doc, double default_motion_timeout) {
  addInput<sensor_msgs::JointState>("configuration", target_doc);
  addOutput<sensor_msgs::JointState>("reached", "joint angles reached, stamped when the motion ended");
  addProperty<std::string>("action", default_action, action_doc);
  addProperty<double>("speed_scale", 1.0, "fraction of the joints' maximum velocity").range(0.01, 1.0);
  addProperty<double>("server_timeout", 5.0, "seconds to wait for the action server").range(0.0, 600.0);
  addProperty<double>("motion_timeout", default_motion_timeout, "seconds to wait for the motion to finish")
      .range(0.1, 3600.0);
}

void MoveJointGroup::process(Context& ctx) {
  const auto target = ctx.input<sensor_msgs::JointState>("configuration");
  if (target->name.size() != target->position.size()) {
    throw BlockError("input 'configuration': " + std::to_string(target->name.size()) + " names but " +
                     std::to_string(target->position.size()) + " positions");
  }
  ctx.output("reached", moveJoints(ctx.property<std::string>("action"), *target,
                                             ctx.property<double>("speed_scale"), ctx.property<double>("server_timeout"),
                                             ctx.property<double>("motion_timeout")));
}

}  // namespace blocks
}  // namespace imagenets
