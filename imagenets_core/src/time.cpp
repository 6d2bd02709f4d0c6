#include "imagenets/time.h"

#include <ros/init.h>

namespace imagenets {
ros::Time now() {
  if (ros::isInitialized() && ros::Time::isValid()) return ros::Time::now();
  ros::WallTime wall = ros::WallTime::now();
  return ros::Time(wall.sec, wall.nsec);
}
}  // namespace imagenets
