#pragma once
#include <ros/time.h>

namespace imagenets {
// ROS time in a node; wall-clock time in a program that embeds nets without ROS.
ros::Time now();
}  // namespace imagenets
