#include "settled_grab.h"

#include <cmath>
#include <map>
#include <mutex>

#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>

#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {
namespace hardware {
namespace {

// The time from which the robot has been still for settle_time.
ros::Time waitUntilSettled(Context& ctx, const ros::WallTime& deadline) {
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

}  // namespace

std::vector<PropertySpec> settledGrabProperties(const std::string& camera, const std::string& camera_doc) {
  std::vector<PropertySpec> p;
  p.emplace_back("camera", PropertyTraits<std::string>::kind, camera, camera_doc);
  p.emplace_back("joint_states", PropertyTraits<std::string>::kind, std::string("joint_states"),
                 "topic telling whether the robot moves");
  p.emplace_back("settle_time", PropertyTraits<double>::kind, 0.2, "seconds without joint motion before grabbing");
  p.back().range(0.0, 10.0);
  p.emplace_back("still_velocity", PropertyTraits<double>::kind, 1e-4, "joint speed (rad/s) below which a joint is still");
  p.back().range(0.0, 1.0);
  p.emplace_back("trigger", PropertyTraits<bool>::kind, true,
                 "call NS/trigger (std_srvs/Trigger) instead of waiting for the free-running rate");
  p.emplace_back("retrigger", PropertyTraits<double>::kind, 0.25, "seconds after which a trigger without images is repeated");
  p.back().range(0.01, 60.0);
  p.emplace_back("timeout", PropertyTraits<double>::kind, 10.0, "seconds to wait for the robot to settle and for the images");
  p.back().range(0.1, 600.0);
  return p;
}

std::vector<GrabbedImage> grabSettled(Context& ctx, const std::vector<std::string>& cameras) {
  ensureRosNode();
  const double timeout = ctx.property<double>("timeout");
  const std::string ns = ctx.property<std::string>("camera");
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  // Subscribed first, so the connections come up while the robot settles.
  ros::CallbackQueue queue;
  ros::NodeHandle nh;
  nh.setCallbackQueue(&queue);
  std::mutex m;
  const size_t n = cameras.size();
  std::vector<std::map<ros::Time, sensor_msgs::ImageConstPtr>> images(n);
  std::vector<std::map<ros::Time, sensor_msgs::CameraInfoConstPtr>> infos(n);
  auto keep = [&m](auto& store) {
    return [&store, &m](const auto& msg) {
      std::lock_guard<std::mutex> lock(m);
      store[msg->header.stamp] = msg;
      if (store.size() > 8) store.erase(store.begin());
    };
  };
  std::vector<ros::Subscriber> image_subs, info_subs;
  std::string topics;
  for (size_t i = 0; i < n; ++i) {
    const std::string prefix = cameras[i].empty() ? ns : ns + "/" + cameras[i];
    image_subs.push_back(nh.subscribe<sensor_msgs::Image>(prefix + "/image_raw", 4, keep(images[i])));
    info_subs.push_back(nh.subscribe<sensor_msgs::CameraInfo>(prefix + "/camera_info", 4, keep(infos[i])));
    topics += (i == 0 ? "'" : " and '") + image_subs.back().getTopic() + "'";
  }
  auto connected = [&] {
    for (const auto& s : image_subs) {
      if (s.getNumPublishers() == 0) return false;
    }
    return true;
  };
  const ros::Time settled = waitUntilSettled(ctx, deadline);
  // Let the subscriptions connect before triggering, or the triggered images are missed.
  while (!connected() && ros::WallTime::now() < deadline) queue.callAvailable(ros::WallDuration(0.01));
  if (!connected()) {
    throw BlockError("no publisher on " + topics + " within " + std::to_string(timeout) + " s (property timeout)");
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
      // Again if no images came (a frame dropped, or the first one sent before our subscription connected).
      next_trigger = ros::WallTime::now() + ros::WallDuration(ctx.property<double>("retrigger"));
    }
    queue.callAvailable(ros::WallDuration(0.01));
    std::lock_guard<std::mutex> lock(m);
    for (const auto& kv : images[0]) {
      if (kv.first < settled) continue;
      bool complete = true;
      for (size_t i = 0; i < n && complete; ++i) complete = images[i].count(kv.first) && infos[i].count(kv.first);
      if (!complete) continue;
      std::vector<GrabbedImage> out;
      for (size_t i = 0; i < n; ++i) out.push_back({images[i][kv.first], infos[i][kv.first]});
      return out;
    }
  }
  throw BlockError("camera silent: no " + std::string(n > 1 ? "synchronised pair" : "image with camera_info") + " on " +
                   topics + " within " + std::to_string(timeout) + " s (property timeout)");
}

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
