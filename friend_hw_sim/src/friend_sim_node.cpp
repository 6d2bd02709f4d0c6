// friend_sim_node: the simulated FRIEND robot (see friend_hw_sim/friend_sim.h for its interface).
#include <ros/ros.h>

#include "friend_hw_sim/friend_sim.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "friend_sim");
  ros::NodeHandle nh, pnh("~");
  try {
    friend_hw_sim::FriendSim sim(nh, pnh);
    // Several threads: a camera trigger (rendering) must not stall joint_states or the actions.
    ros::AsyncSpinner spinner(4);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("friend_sim: %s", e.what());
    return 1;
  }
  return 0;
}
