#include "imagenets/blocks/ros_access.h"

#include <map>
#include <mutex>

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
