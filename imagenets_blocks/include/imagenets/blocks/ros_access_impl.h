// Template part of ros_access.h.
#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

#include <ros/callback_queue.h>

#include "imagenets/block.h"

namespace imagenets {
namespace blocks {
namespace hardware {

template <class M>
boost::shared_ptr<const M> waitForMessage(const std::string& topic, double timeout,
                                          std::function<bool(const M&)> accept) {
  ensureRosNode();
  // A private queue, spun here: works whether or not the host process spins the global queue.
  ros::CallbackQueue queue;
  ros::NodeHandle nh;
  nh.setCallbackQueue(&queue);
  boost::shared_ptr<const M> result;
  ros::Subscriber sub = nh.subscribe<M>(topic, 5, [&](const boost::shared_ptr<const M>& m) {
    if (!result && (!accept || accept(*m))) result = m;
  });
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!result && ros::WallTime::now() < end && ros::ok()) queue.callAvailable(ros::WallDuration(0.01));
  if (!result) {
    throw BlockError("no message on '" + sub.getTopic() + "' within " + std::to_string(timeout) + " s (" +
                     std::to_string(sub.getNumPublishers()) + " publishers)");
  }
  return result;
}

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
