// Moves a joint group (an arm, a pan-tilt head) to a configuration through a
// control_msgs/FollowJointTrajectory action server: what ros_control's joint_trajectory_controller
// serves on real robots (arm_controller/follow_joint_trajectory, head_controller/...). The goal is
// one waypoint at the configuration, reached from rest to rest in the time the speed limit allows
// (property max_velocity: the fastest joint's peak speed), with the block's path and goal
// tolerances; it starts from the joints' positions on joint_states. A goal the controller rejects
// or aborts, a missing or lost server, another client's goal preempting this one, or a motion
// that does not end in time fail the block with the controller's error code and text and, from
// the joints measured afterwards, which joint was outside which tolerance; when the run is
// cancelled the goal is cancelled too.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include <boost/make_shared.hpp>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <ros/master.h>
#include <sensor_msgs/JointState.h>

#include "follow_joint_trajectory.h"
#include "imagenets/blocks/action_clients.h"
#include "imagenets/blocks/ros_access.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {
namespace {

using control_msgs::FollowJointTrajectoryAction;
using control_msgs::FollowJointTrajectoryResult;
using hardware::ActionClientLease;

std::vector<std::string> splitNames(const std::string& text) {
  std::vector<std::string> names;
  std::string name;
  std::istringstream in(text);
  while (in >> name) {
    std::string part;
    std::istringstream pieces(name);
    while (std::getline(pieces, part, ',')) {
      if (!part.empty()) names.push_back(part);
    }
  }
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// The FollowJointTrajectory servers the master knows (their feedback topics), for an error.
std::string knownServers() {
  ros::master::V_TopicInfo topics;
  if (!ros::master::getTopics(topics)) return "";
  std::set<std::string> servers;
  const std::string suffix = "/feedback";
  for (const auto& t : topics) {
    if (t.datatype == "control_msgs/FollowJointTrajectoryActionFeedback" && t.name.size() > suffix.size()) {
      servers.insert(t.name.substr(0, t.name.size() - suffix.size()));
    }
  }
  if (servers.empty()) return "; the master knows no FollowJointTrajectory server";
  return "; FollowJointTrajectory servers the master knows: " + joined({servers.begin(), servers.end()});
}

}  // namespace

class FollowJointTrajectory : public Block {
 public:
  FollowJointTrajectory() {
    addInput<sensor_msgs::JointState>("configuration", "target joint names and positions (rad); none (and no property joints): reached at once");
    addOutput<sensor_msgs::JointState>(
        "reached", "the goal's joints as joint_states measured them after the motion, stamped then");
    addProperty<std::string>("action", "arm_controller/follow_joint_trajectory",
                             "control_msgs/FollowJointTrajectory action server (e.g. head_controller/follow_joint_trajectory)");
    addProperty<std::string>("joints", "",
                             "the controller's joints, separated by spaces or commas: the goal names them all, those "
                             "the input leaves out keep their position; empty: the input's joints");
    addProperty<std::string>("joint_states", "joint_states", "sensor_msgs/JointState topic the motion starts from");
    addProperty<double>("max_velocity", 0.5, "speed limit (rad/s): the fastest joint's peak speed sets the duration")
        .range(0.001, 100.0);
    addProperty<double>("min_duration", 0.2, "shortest trajectory (s), for tiny motions").range(0.0, 3600.0);
    addProperty<double>("path_tolerance", 0.0,
                        "rad each joint may deviate while moving (0: the controller's default, < 0: none)")
        .range(-1.0, 10.0);
    addProperty<double>("goal_tolerance", 0.01,
                        "rad each joint may end from its goal (0: the controller's default, < 0: none)")
        .range(-1.0, 10.0);
    addProperty<double>("goal_time_tolerance", 1.0,
                        "s after the trajectory's end by which the goal tolerance must hold (0: the controller's)")
        .range(0.0, 600.0);
    addProperty<double>("server_timeout", 5.0, "seconds to wait for the action server").range(0.0, 600.0);
    addProperty<double>("state_timeout", 2.0, "seconds to wait for joint_states").range(0.01, 600.0);
    addProperty<double>("result_timeout", 30.0,
                        "seconds to wait for the result beyond the trajectory's duration and goal_time_tolerance")
        .range(0.1, 3600.0);
  }

  void process(Context& ctx) override {
    const auto target = ctx.input<sensor_msgs::JointState>("configuration");
    checkConfiguration(*target);
    if (target->name.empty() && splitNames(ctx.property<std::string>("joints")).empty()) {
      // Nothing to move (a head without joints: a camera on a stand): reached at once, no server
      // asked, as a controller would answer a goal without joints.
      auto reached = boost::make_shared<sensor_msgs::JointState>();
      reached->header.stamp = ros::Time::now();
      ctx.output("reached", reached);
      return;
    }
    const std::vector<std::string> joints = goalJoints(ctx, *target);
    const std::string topic = ctx.property<std::string>("joint_states");
    const double state_timeout = ctx.property<double>("state_timeout");
    hardware::ensureRosNode();
    const auto now = hardware::jointPositions(topic, joints, state_timeout);
    std::vector<double> goal_positions = now->position;
    for (size_t i = 0; i < target->name.size(); ++i) {
      goal_positions[std::find(joints.begin(), joints.end(), target->name[i]) - joints.begin()] = target->position[i];
    }
    const auto motion = hardware::pointToPoint(joints, now->position, goal_positions, ctx.property<double>("max_velocity"),
                                               ctx.property<double>("min_duration"));
    hardware::TrajectoryTolerances tolerances;
    tolerances.path = ctx.property<double>("path_tolerance");
    tolerances.goal = ctx.property<double>("goal_tolerance");
    tolerances.goal_time = ctx.property<double>("goal_time_tolerance");
    move(ctx, motion, tolerances);
    // Where the joints are now: joint_states stamped after the result.
    ctx.output("reached", hardware::jointPositions(topic, joints, state_timeout, ros::Time::now()));
  }

 private:
  static void checkConfiguration(const sensor_msgs::JointState& target) {
    if (target.name.size() != target.position.size()) {
      throw BlockError("input 'configuration': " + std::to_string(target.name.size()) + " names but " +
                       std::to_string(target.position.size()) + " positions");
    }
    for (size_t i = 0; i < target.name.size(); ++i) {
      if (!std::isfinite(target.position[i])) {
        throw BlockError("input 'configuration': joint '" + target.name[i] + "' has no finite position");
      }
      if (std::count(target.name.begin(), target.name.end(), target.name[i]) > 1) {
        throw BlockError("input 'configuration' names joint '" + target.name[i] + "' twice");
      }
    }
  }

  // The goal's joints: the controller's (property joints) or the input's.
  static std::vector<std::string> goalJoints(Context& ctx, const sensor_msgs::JointState& target) {
    std::vector<std::string> joints = splitNames(ctx.property<std::string>("joints"));
    if (target.name.empty()) {
      throw BlockError("input 'configuration' names no joint of the controller's (property joints: " + joined(joints) + ")");
    }
    if (joints.empty()) joints = target.name;
    for (const auto& n : target.name) {
      if (std::find(joints.begin(), joints.end(), n) == joints.end()) {
        throw BlockError("input 'configuration' names joint '" + n + "', which is not one of the controller's (property joints: " +
                         joined(joints) + ")");
      }
    }
    return joints;
  }

  // Sends the goal and waits for its end; BlockError saying why when it did not succeed.
  static void move(Context& ctx, const hardware::PointToPointMotion& motion, const hardware::TrajectoryTolerances& tolerances) {
    ActionClientLease<FollowJointTrajectoryAction> lease(ctx.property<std::string>("action"));
    const std::string& action = lease.action();
    auto& client = lease.client();
    const double server_timeout = ctx.property<double>("server_timeout");
    if (!lease.waitUntil([&] { return client.isServerConnected() || ctx.cancelled(); }, server_timeout)) {
      throw BlockError("action server '" + action + "' not available after " + std::to_string(server_timeout) +
                       " s (property server_timeout; is its controller running?)" + knownServers());
    }
    if (ctx.cancelled()) throw RunCancelled();
    const ros::WallTime sent = ros::WallTime::now();
    client.sendGoal(hardware::trajectoryGoal(motion, tolerances));
    bool lost = false;  // the server went away mid-motion (the robot's driver stopped): fail at once
    const double wait = motion.duration + std::max(tolerances.goal_time, 0.0) + ctx.property<double>("result_timeout");
    const bool finished = lease.waitUntil(
        [&] {
          lost = !client.getState().isDone() && !client.isServerConnected();
          return lost || client.getState().isDone() || ctx.cancelled();
        },
        wait);
    const double elapsed = (ros::WallTime::now() - sent).toSec();
    if (lost) {
      client.cancelGoal();
      lease.reset();
      throw BlockError("action server '" + action + "' lost during the motion (the robot's driver stopped?)");
    }
    if (ctx.cancelled() && !client.getState().isDone()) {
      client.cancelGoal();  // the controller stops the joints where they are
      lease.waitUntil([&] { return client.getState().isDone(); }, 2.0);
      throw RunCancelled();
    }
    if (!finished) {
      client.cancelGoal();
      throw BlockError("'" + action + "' did not finish within " + std::to_string(wait) +
                       " s (the trajectory's duration, goal_time_tolerance and property result_timeout); goal canceled");
    }
    checkResult(ctx, action, client.getState(), client.getResult(), motion, tolerances, elapsed);
  }

  // A goal that did not succeed: the controller's code and text and, from the joints measured
  // now, which joint was outside which tolerance.
  static void checkResult(Context& ctx, const std::string& action, const actionlib::SimpleClientGoalState& state,
                          const FollowJointTrajectoryResult::ConstPtr& result, const hardware::PointToPointMotion& motion,
                          const hardware::TrajectoryTolerances& tolerances, double elapsed) {
    const int code = result ? result->error_code : FollowJointTrajectoryResult::SUCCESSFUL;
    if (state == actionlib::SimpleClientGoalState::SUCCEEDED && code == FollowJointTrajectoryResult::SUCCESSFUL) return;
    sensor_msgs::JointStatePtr measured;
    try {
      measured = hardware::jointPositions(ctx.property<std::string>("joint_states"), motion.joints,
                                          ctx.property<double>("state_timeout"));
    } catch (const BlockError&) {
      // Said without the measurement.
    }
    const std::string text = result && !result->error_string.empty() ? result->error_string : state.getText();
    throw BlockError(hardware::trajectoryFailure(action, state.toString(), code, text, motion, tolerances, elapsed,
                                                 measured.get()));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::FollowJointTrajectory, "imagenets/FollowJointTrajectory", "hardware",
                         "Moves joints to a configuration (control_msgs/FollowJointTrajectory action)");
