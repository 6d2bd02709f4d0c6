// calibration_node: see imagenets_calibration/calibration_node.h.
#include <ros/ros.h>

#include "imagenets_calibration/calibration_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "calibration");
  ros::NodeHandle nh, pnh("~");
  // Service, action, sensor callbacks and the action clients each need a thread: a calibration
  // blocks its callback while the arm moves and images arrive.
  ros::AsyncSpinner spinner(4);
  spinner.start();
  try {
    imagenets_calibration::CalibrationNode node(nh, pnh);
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", ros::this_node::getName().c_str(), e.what());
    return 1;
  }
  return 0;
}
