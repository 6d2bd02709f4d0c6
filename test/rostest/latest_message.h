// The newest message of a topic, for the rostest nodes: wait for one, or for one stamped at or
// after a given time (a message from after an action, not an old latched one).
#pragma once

#include <mutex>
#include <string>

#include <ros/ros.h>

template <class M>
class LatestMessage {
 public:
  explicit LatestMessage(const std::string& topic) { sub_ = nh_.subscribe(topic, 5, &LatestMessage::received, this); }

  boost::shared_ptr<const M> get() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_;
  }
  // Null after `timeout` seconds (wall time) without a message.
  boost::shared_ptr<const M> wait(double timeout) {
    return waitFor(timeout, [](const M&) { return true; });
  }
  boost::shared_ptr<const M> waitFrom(const ros::Time& after, double timeout) {
    return waitFor(timeout, [&after](const M& m) { return m.header.stamp >= after; });
  }

 private:
  template <class Accept>
  boost::shared_ptr<const M> waitFor(double timeout, const Accept& accept) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
    for (;;) {
      auto m = get();
      if (m && accept(*m)) return m;
      if (ros::WallTime::now() >= end || !ros::ok()) return nullptr;
      ros::WallDuration(0.01).sleep();
    }
  }
  void received(const boost::shared_ptr<const M>& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    last_ = m;
  }
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  boost::shared_ptr<const M> last_;
};
