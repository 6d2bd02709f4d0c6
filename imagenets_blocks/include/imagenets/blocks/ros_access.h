// Shared plumbing of the hardware blocks: they reach the robot (or the simulator) through ROS
// like any driver client. A block may run inside a node (nodelet host: ROS is up) or inside the
// command line tool (no node yet): ensureRosNode() starts an anonymous node on first use and
// reports a missing master clearly. Every wait has a timeout and names what it waited for.
#pragma once

#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

namespace tf2_ros {
class Buffer;
}

namespace imagenets {
namespace blocks {
namespace hardware {

// Starts a ROS node for this process if none runs yet; throws BlockError when no master answers.
void ensureRosNode();

// Waits for the next message on `topic` that arrives after the call (or satisfies `accept`).
template <class M>
boost::shared_ptr<const M> waitForMessage(const std::string& topic, double timeout,
                                          std::function<bool(const M&)> accept = nullptr);

// Positions of the joints `names` from the sensor_msgs/JointState messages on `topic`, gathered
// over the messages arriving within `timeout` s (a robot may publish its joint groups in separate
// messages), from messages stamped at or after `after` only (zero: any). The result lists `names`
// in that order (velocities too where every message used had them), stamped like the newest
// message used. Throws BlockError naming the joints not seen and those the topic did carry.
sensor_msgs::JointStatePtr jointPositions(const std::string& topic, const std::vector<std::string>& names,
                                          double timeout, const ros::Time& after = ros::Time());

// The process's TF buffer, filled by one tf2_ros listener (own spin thread) started on first use;
// call ensureRosNode() first. Shared so that every block sees the history since the first lookup.
tf2_ros::Buffer& tfBuffer();

// Pose of `source` in `target` at `stamp` (0 = latest), waiting up to `timeout` s. Throws
// BlockError naming both frames, the time and TF's reason (and the frames TF knows when one of
// them is unknown).
geometry_msgs::TransformStamped lookupTransform(const tf2_ros::Buffer& buffer, const std::string& target,
                                                const std::string& source, const ros::Time& stamp, double timeout);

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets

#include "imagenets/blocks/ros_access_impl.h"
