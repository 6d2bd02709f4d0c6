// Grabs one synchronised stereo pair (left/right image + camera_info with identical stamps) taken
// after the robot has settled: it waits until joint_states report no motion for `settle_time`,
// then (optionally) triggers the camera, and takes the first pair stamped after that moment.
#include <cmath>
#include <mutex>

#include <ros/callback_queue.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class GrabStereoPair : public Block {
 public:
  GrabStereoPair() {
    addOptionalInput<sensor_msgs::JointState>("after", "grab only after this (e.g. MoveHead.reached): orders the net");
    addOutput<sensor_msgs::Image>("left_image", "left image_raw");
    addOutput<sensor_msgs::Image>("right_image", "right image_raw, same stamp");
    addOutput<sensor_msgs::CameraInfo>("left_info", "left camera_info, same stamp");
    addOutput<sensor_msgs::CameraInfo>("right_info", "right camera_info, same stamp");
    addProperty<std::string>("camera", "stereo", "camera namespace: NS/{left,right}/{image_raw,camera_info}");
    addProperty<std::string>("joint_states", "joint_states", "topic telling whether the robot moves");
    addProperty<double>("settle_time", 0.2, "seconds without joint motion before grabbing").range(0.0, 10.0);
    addProperty<double>("still_velocity", 1e-4, "joint speed (rad/s) below which a joint is still").range(0.0, 1.0);
    addProperty<bool>("trigger", true, "call NS/trigger (std_srvs/Trigger) instead of waiting for the free-running rate");
    addProperty<double>("retrigger", 0.25, "seconds after which a trigger without a pair is repeated").range(0.01, 60.0);
    addProperty<double>("timeout", 10.0, "seconds to wait for the robot to settle and for the pair").range(0.1, 600.0);
  }

  void process(Context& ctx) override {
    hardware::ensureRosNode();
    const double timeout = ctx.property<double>("timeout");
    const std::string ns = ctx.property<std::string>("camera");
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    // Subscribed first, so the connections come up while the robot settles.
    ros::CallbackQueue queue;
    ros::NodeHandle nh;
    nh.setCallbackQueue(&queue);
    std::mutex m;
    std::map<ros::Time, sensor_msgs::ImageConstPtr> left, right;
    std::map<ros::Time, sensor_msgs::CameraInfoConstPtr> left_info, right_info;
    auto keep = [&](auto& store) {
      return [&store, &m](const auto& msg) {
        std::lock_guard<std::mutex> lock(m);
        store[msg->header.stamp] = msg;
        if (store.size() > 8) store.erase(store.begin());
      };
    };
    auto s1 = nh.subscribe<sensor_msgs::Image>(ns + "/left/image_raw", 4, keep(left));
    auto s2 = nh.subscribe<sensor_msgs::Image>(ns + "/right/image_raw", 4, keep(right));
    auto s3 = nh.subscribe<sensor_msgs::CameraInfo>(ns + "/left/camera_info", 4, keep(left_info));
    auto s4 = nh.subscribe<sensor_msgs::CameraInfo>(ns + "/right/camera_info", 4, keep(right_info));
    const ros::Time settled = waitUntilSettled(ctx, deadline);
    // Let the subscriptions connect before triggering, or the triggered pair is missed.
    while ((s1.getNumPublishers() == 0 || s2.getNumPublishers() == 0) && ros::WallTime::now() < deadline) {
      queue.callAvailable(ros::WallDuration(0.01));
    }
    if (s1.getNumPublishers() == 0 || s2.getNumPublishers() == 0) {
      throw BlockError("no publisher on '" + s1.getTopic() + "' / '" + s2.getTopic() + "' within " +
                       std::to_string(timeout) + " s (property timeout)");
    }
    ros::WallTime next_trigger;
    while (ros::WallTime::now() < deadline && ros::ok()) {
      if (ctx.property<bool>("trigger") && ros::WallTime::now() >= next_trigger) {
        std_srvs::Trigger t;
        const std::string service = ros::names::resolve(ns + "/trigger");
        if (!ros::service::call(service, t) || !t.response.success) {
          throw BlockError("camera trigger service '" + service + "' failed: " +
                           (t.response.message.empty() ? "not available" : t.response.message));
        }
        // Again if no pair came (a frame dropped, or the first one sent before our subscription connected).
        next_trigger = ros::WallTime::now() + ros::WallDuration(ctx.property<double>("retrigger"));
      }
      queue.callAvailable(ros::WallDuration(0.01));
      std::lock_guard<std::mutex> lock(m);
      for (const auto& kv : left) {
        if (kv.first >= settled && right.count(kv.first) && left_info.count(kv.first) && right_info.count(kv.first)) {
          ctx.output("left_image", kv.second);
          ctx.output("right_image", right[kv.first]);
          ctx.output("left_info", left_info[kv.first]);
          ctx.output("right_info", right_info[kv.first]);
          return;
        }
      }
    }
    throw BlockError("camera silent: no synchronised pair on '" + s1.getTopic() + "' and '" + s2.getTopic() + "' within " +
                     std::to_string(timeout) + " s (property timeout)");
  }

 private:
  // Returns the time from which the robot has been still for settle_time.
  ros::Time waitUntilSettled(Context& ctx, const ros::WallTime& deadline) const {
    const double settle = ctx.property<double>("settle_time"), still = ctx.property<double>("still_velocity");
    ros::CallbackQueue queue;
    ros::NodeHandle nh;
    nh.setCallbackQueue(&queue);
    ros::Time still_since, settled;
    bool any = false;
    auto sub = nh.subscribe<sensor_msgs::JointState>(ctx.property<std::string>("joint_states"), 20,
                                                     [&](const sensor_msgs::JointStateConstPtr& js) {
                                                       any = true;
                                                       bool moving = false;
                                                       for (double v : js->velocity) moving |= std::abs(v) > still;
                                                       if (moving || still_since.isZero()) still_since = js->header.stamp;
                                                       if (!moving && (js->header.stamp - still_since).toSec() >= settle)
                                                         settled = js->header.stamp;
                                                     });
    while (settled.isZero() && ros::WallTime::now() < deadline && ros::ok()) queue.callAvailable(ros::WallDuration(0.01));
    if (settled.isZero()) {
      throw BlockError(any ? "the robot did not settle within the timeout (joint_states still report motion)"
                           : "no joint_states on '" + sub.getTopic() + "' within the timeout (property joint_states)");
    }
    return settled;
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::GrabStereoPair, "imagenets/GrabStereoPair", "hardware",
                         "A synchronised stereo pair (images + camera_info) taken after the robot has settled");
