#include "ros_access.h"

#include <map>
#include <mutex>

#include <actionlib/client/simple_action_client.h>
#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "imagenets/MoveJointsAction.h"
#include "imagenets/calling_thread_queue.h"

namespace imagenets {
namespace blocks {
namespace hardware {

void ensureRosNode() {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  if (!ros::isInitialized()) {
    int argc = 0;
    ros::init(argc, nullptr, "imagenets_hardware", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  }
  if (!ros::master::check()) {
    throw BlockError("no ROS master at " + ros::master::getURI() + " (start the robot or `roslaunch imagenets friend_sim.launch`)");
  }
  if (!ros::isStarted()) ros::start();
}

namespace {

// One client per action server, kept between motions (connecting one takes a few hundred ms, more
// than many motions), each on its own calling-thread queue and used by one motion at a time. Its
// queue collects the server's status messages while idle: a client idle for a minute is
// replaced, which bounds that backlog.
struct MoveConnection {
  CallingThreadQueue queue;
  actionlib::SimpleActionClient<imagenets::MoveJointsAction> client;
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

}  // namespace

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
  imagenets::MoveJointsGoal goal;
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

tf2_ros::Buffer& tfBuffer() {
  // Never destroyed: the listener's thread must not outlive ROS's shutdown order at exit.
  static tf2_ros::Buffer* buffer = [] {
    auto* b = new tf2_ros::Buffer(ros::Duration(30.0));
    new tf2_ros::TransformListener(*b, ros::NodeHandle(), true);
    return b;
  }();
  return *buffer;
}

geometry_msgs::TransformStamped lookupTransform(const tf2_ros::Buffer& buffer, const std::string& target,
                                                const std::string& source, const ros::Time& stamp, double timeout) {
  std::string reason;
  if (buffer.canTransform(target, source, stamp, ros::Duration(timeout), &reason)) {
    try {
      return buffer.lookupTransform(target, source, stamp);
    } catch (const tf2::TransformException& e) {
      reason = e.what();
    }
  }
  std::string known;
  if (!buffer._frameExists(target) || !buffer._frameExists(source)) {
    std::vector<std::string> frames;
    buffer._getFrameStrings(frames);
    for (const auto& f : frames) known += (known.empty() ? "" : ", ") + f;
    known = "; frames TF knows: " + (known.empty() ? std::string("none") : known);
  }
  char when[64];
  std::snprintf(when, sizeof when, "%.3f", stamp.toSec());
  throw BlockError("no transform from '" + source + "' to '" + target + "' (properties source_frame, target_frame) at " +
                   (stamp.isZero() ? std::string("the latest time") : std::string("t = ") + when) + " within " +
                   std::to_string(timeout) + " s: " + (reason.empty() ? "not available" : reason) + known);
}

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
