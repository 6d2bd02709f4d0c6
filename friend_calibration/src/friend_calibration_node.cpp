// friend_calibration_node: see friend_calibration/calibration_node.h.
#include <ros/ros.h>

#include "friend_calibration/calibration_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "friend_calibration");
  ros::NodeHandle nh, pnh("~");
  // Service, action, sensor callbacks and the action clients each need a thread: a calibration
  // blocks its callback while the arm moves and images arrive.
  ros::AsyncSpinner spinner(4);
  spinner.start();
  try {
    friend_calibration::CalibrationNode node(nh, pnh);
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("friend_calibration: %s", e.what());
    return 1;
  }
  return 0;
}
