#include "move_joint_group.h"

#include <map>
#include <mutex>

#include <actionlib/client/simple_action_client.h>

#include "friend_msgs/MoveJointsAction.h"
#include "imagenets/blocks/ros_access.h"
#include "imagenets/calling_thread_queue.h"

namespace imagenets {
namespace blocks {
namespace {

using hardware::ensureRosNode;

// One client per action server, kept between motions (connecting one takes a few hundred ms, more
// than many motions), each on its own calling-thread queue and used by one motion at a time. Its
// queue collects the server's status messages while idle: a client idle for a minute is
// replaced, which bounds that backlog.
struct MoveConnection {
  CallingThreadQueue queue;
  actionlib::SimpleActionClient<friend_msgs::MoveJointsAction> client;
  explicit MoveConnection(const std::string& action) : client(queue.nodeHandle(), action, false) {}
};
struct MoveClient {
  std::mutex busy;
  std::unique_ptr<MoveConnection> connection;
  ros::WallTime last_used;
};

MoveClient& moveClient(const std::string& action) {
  static std::mutex mutex;
  // Never destroyed: actionlib clients must not be torn down after ROS has shut down at exit.
  static auto* clients = new std::map<std::string, std::unique_ptr<MoveClient>>();
  std::lock_guard<std::mutex> lock(mutex);
  auto& c = (*clients)[ros::names::resolve(action)];
  if (!c) c = std::make_unique<MoveClient>();
  return *c;
}

// Sends a friend_msgs/MoveJoints goal and waits for the result; returns the reached positions.
// Throws BlockError naming the action when the server is missing, rejects, aborts or times out.
sensor_msgs::JointStatePtr moveJoints(const std::string& action, const sensor_msgs::JointState& target,
                                      double speed_scale, double server_timeout, double motion_timeout) {
  ensureRosNode();
  MoveClient& move = moveClient(action);
  std::lock_guard<std::mutex> lock(move.busy);
  if (!move.connection || (ros::WallTime::now() - move.last_used).toSec() > 60.0) {
    move.connection.reset();
    move.connection = std::make_unique<MoveConnection>(action);
  }
  struct Used {
    MoveClient& m;
    ~Used() { m.last_used = ros::WallTime::now(); }
  } used{move};
  auto& client = move.connection->client;
  CallingThreadQueue& queue = move.connection->queue;
  if (!queue.waitUntil([&client] { return client.isServerConnected(); }, server_timeout)) {
    throw BlockError("action server '" + ros::names::resolve(action) + "' not available after " +
                     std::to_string(server_timeout) + " s (property server_timeout)");
  }
  friend_msgs::MoveJointsGoal goal;
  goal.joint_names = target.name;
  goal.positions = target.position;
  goal.speed_scale = speed_scale;
  client.sendGoal(goal);
  bool lost = false;  // the server went away mid-motion (the robot's driver stopped): fail at once
  const bool finished = queue.waitUntil(
      [&] {
        lost = !client.getState().isDone() && !client.isServerConnected();
        return lost || client.getState().isDone();
      },
      motion_timeout);
  if (lost) {
    client.cancelGoal();
    move.connection.reset();
    throw BlockError("action server '" + ros::names::resolve(action) +
                     "' lost during the motion (the robot's driver / friend_sim stopped?)");
  }
  if (!finished) {
    client.cancelGoal();
    throw BlockError("'" + ros::names::resolve(action) + "' did not finish within " + std::to_string(motion_timeout) +
                     " s (property motion_timeout); goal canceled");
  }
  const auto state = client.getState();
  if (state != actionlib::SimpleClientGoalState::SUCCEEDED) {
    throw BlockError("'" + ros::names::resolve(action) + "' " + state.toString() + ": " + state.getText());
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
