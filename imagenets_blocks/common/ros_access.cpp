#include "imagenets/blocks/ros_access.h"

#include <map>
#include <mutex>
#include <set>

#include <boost/make_shared.hpp>
#include <ros/callback_queue.h>

#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>


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
    throw BlockError("no ROS master at " + ros::master::getURI() + " (start the robot, its simulator or a bag)");
  }
  if (!ros::isStarted()) ros::start();
}

sensor_msgs::JointStatePtr jointPositions(const std::string& topic, const std::vector<std::string>& names,
                                          double timeout, const ros::Time& after) {
  ensureRosNode();
  std::map<std::string, size_t> wanted;
  for (size_t i = 0; i < names.size(); ++i) wanted.emplace(names[i], i);
  auto out = boost::make_shared<sensor_msgs::JointState>();
  out->name = names;
  out->position.assign(names.size(), 0.0);
  out->velocity.assign(names.size(), 0.0);
  std::vector<bool> seen(names.size(), false);
  bool velocities = true;
  size_t missing = names.size();
  std::set<std::string> carried;
  ros::CallbackQueue queue;  // spun here: works whether or not the host process spins
  ros::NodeHandle nh;
  nh.setCallbackQueue(&queue);
  ros::Subscriber sub = nh.subscribe<sensor_msgs::JointState>(
      topic, 20, [&](const sensor_msgs::JointStateConstPtr& m) {
        if (missing == 0 || (!after.isZero() && m->header.stamp < after)) return;
        const bool has_velocity = m->velocity.size() == m->name.size();
        for (size_t i = 0; i < m->name.size() && i < m->position.size(); ++i) {
          carried.insert(m->name[i]);
          const auto it = wanted.find(m->name[i]);
          if (it == wanted.end()) continue;
          out->position[it->second] = m->position[i];
          if (has_velocity) out->velocity[it->second] = m->velocity[i];
          velocities = velocities && has_velocity;
          if (!seen[it->second]) {
            seen[it->second] = true;
            --missing;
          }
          if (m->header.stamp > out->header.stamp) out->header.stamp = m->header.stamp;
        }
      });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (missing > 0 && ros::WallTime::now() < end && ros::ok()) queue.callAvailable(ros::WallDuration(0.01));
  if (missing > 0) {
    std::string absent, has;
    for (size_t i = 0; i < names.size(); ++i) {
      if (!seen[i]) absent += (absent.empty() ? "'" : ", '") + names[i] + "'";
    }
    for (const auto& n : carried) has += (has.empty() ? "" : ", ") + n;
    throw BlockError("no position of joint " + absent + " on '" + sub.getTopic() + "' within " +
                     std::to_string(timeout) + " s (" + std::to_string(sub.getNumPublishers()) + " publishers; " +
                     (carried.empty() ? std::string("no message") : "its messages name " + has) + ")");
  }
  if (!velocities) out->velocity.clear();
  return out;
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
