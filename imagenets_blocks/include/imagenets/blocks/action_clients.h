// actionlib clients for the hardware blocks: one per action server (and action type), kept
// between goals -- connecting one takes a few hundred ms, more than many motions -- each on its
// own calling-thread queue (imagenets/calling_thread_queue.h) and used by one goal at a time.
// While idle its queue collects the server's status messages: a client idle for a minute is
// replaced, which bounds that backlog.
//
//   ActionClientLease<control_msgs::FollowJointTrajectoryAction> lease("arm_controller/follow_joint_trajectory");
//   lease.waitUntil([&] { return lease.client().isServerConnected(); }, 5.0);
//   lease.client().sendGoal(goal);   // callbacks run only inside lease.waitUntil(), on this thread
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <actionlib/client/simple_action_client.h>
#include <ros/names.h>
#include <ros/time.h>

#include "imagenets/calling_thread_queue.h"

namespace imagenets {
namespace blocks {
namespace hardware {

template <class ActionSpec>
class ActionClientLease {
 public:
  using Client = actionlib::SimpleActionClient<ActionSpec>;

  // Blocks while another goal uses the same server's client. Call ensureRosNode() first.
  explicit ActionClientLease(const std::string& action)
      : action_(ros::names::resolve(action)), slot_(slot(action_)), lock_(slot_.busy) {
    if (!slot_.connection || (ros::WallTime::now() - slot_.last_used).toSec() > 60.0) {
      slot_.connection.reset();
      slot_.connection = std::make_unique<Connection>(action_);
    }
  }
  ~ActionClientLease() { slot_.last_used = ros::WallTime::now(); }
  ActionClientLease(const ActionClientLease&) = delete;
  ActionClientLease& operator=(const ActionClientLease&) = delete;

  const std::string& action() const { return action_; }  // resolved name
  Client& client() { return slot_.connection->client; }
  // Runs the client's callbacks until done() holds (true) or `seconds` pass (false).
  bool waitUntil(const std::function<bool()>& done, double seconds) {
    return slot_.connection->queue.waitUntil(done, seconds);
  }
  // Forgets the connection (its server went away): the next lease connects anew.
  void reset() {
    slot_.connection.reset();
    slot_.connection = std::make_unique<Connection>(action_);
  }

 private:
  struct Connection {
    CallingThreadQueue queue;
    Client client;
    explicit Connection(const std::string& action) : client(queue.nodeHandle(), action, false) {}
  };
  struct Slot {
    std::mutex busy;
    std::unique_ptr<Connection> connection;
    ros::WallTime last_used;
  };
  static Slot& slot(const std::string& action) {
    static std::mutex mutex;
    // Never destroyed: actionlib clients must not be torn down after ROS has shut down at exit.
    static auto* slots = new std::map<std::string, std::unique_ptr<Slot>>();
    std::lock_guard<std::mutex> lock(mutex);
    auto& s = (*slots)[action];
    if (!s) s = std::make_unique<Slot>();
    return *s;
  }

  std::string action_;
  Slot& slot_;
  std::unique_lock<std::mutex> lock_;
};

}  // namespace hardware
}  // namespace blocks
}  // namespace imagenets
