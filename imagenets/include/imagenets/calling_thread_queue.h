// A ROS callback queue handled only by the thread that waits on it, for action clients.
//
// actionlib's SimpleActionClient is not thread-safe: sendGoal() and getState() touch the goal
// handle, the callbacks and the state that its status, feedback and result callbacks rewrite. With
// a multi-threaded spinner (or the client's own spin thread) the two run at once: ThreadSanitizer
// reports the races. A client built on nodeHandle() is called back only inside waitUntil(), on
// the same thread that sends its goals, so nothing overlaps. Its messages wait in the queue until
// then: keep such a client for one task (a motion, a calibration), not for the life of a node.
#pragma once

#include <functional>

#include <ros/callback_queue.h>
#include <ros/node_handle.h>

namespace imagenets {

class CallingThreadQueue {
 public:
  explicit CallingThreadQueue(const ros::NodeHandle& parent = ros::NodeHandle()) : nh_(parent) {
    nh_.setCallbackQueue(&queue_);
  }
  CallingThreadQueue(const CallingThreadQueue&) = delete;
  CallingThreadQueue& operator=(const CallingThreadQueue&) = delete;

  // For the clients (and subscriptions) whose callbacks only waitUntil() may run.
  ros::NodeHandle& nodeHandle() { return nh_; }

  // Runs the queued callbacks until done() holds (true) or `seconds` of wall time pass (false).
  bool waitUntil(const std::function<bool()>& done, double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (!done()) {
      if (ros::WallTime::now() >= end || !ros::ok()) return false;
      queue_.callAvailable(ros::WallDuration(0.005));
    }
    return true;
  }

 private:
  ros::CallbackQueue queue_;  // declared first: it outlives the node handle and its clients
  ros::NodeHandle nh_;
};

}  // namespace imagenets
