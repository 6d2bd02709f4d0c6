// Helpers of the rostest nodes: wait for a condition, call a service once it is there, and the
// newest message of a topic (wait for one, or for one stamped at or after a given time: a message
// from after an action, not an old latched one).
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include <ros/ros.h>

// Waits (an AsyncSpinner delivers messages meanwhile) until `done` holds or `seconds` pass.
inline bool waitFor(const std::function<bool()>& done, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return done();
}

// Calls the service `name` with `request` once it is advertised (e.g. by a node that starts with
// the simulator), waiting up to `timeout` s; its response. Throws naming the service when it is
// not advertised in time or the call fails (a test that does not catch it fails with that).
template <class Service>
typename Service::Response callService(const std::string& name, const typename Service::Request& request = {},
                                       double timeout = 60.0) {
  if (!ros::service::waitForService(name, ros::Duration(timeout))) {
    throw std::runtime_error("service " + name + " not advertised within " + std::to_string(timeout) + " s");
  }
  Service srv;
  srv.request = request;
  if (!ros::service::call(name, srv)) throw std::runtime_error("call of service " + name + " failed");
  return srv.response;
}

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
    return waitUntil(timeout, [](const M&) { return true; });
  }
  boost::shared_ptr<const M> waitFrom(const ros::Time& after, double timeout) {
    return waitUntil(timeout, [&after](const M& m) { return m.header.stamp >= after; });
  }

 private:
  template <class Accept>
  boost::shared_ptr<const M> waitUntil(double timeout, const Accept& accept) {
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
  std::mutex mutex_;
  boost::shared_ptr<const M> last_;
  // Last, so it is destroyed first: unsubscribing waits for a running callback, which must still
  // find mutex_ and last_ alive.
  ros::Subscriber sub_;
};
