#include "imagenets/time.h"

#include <time.h>

#include <ros/init.h>

namespace imagenets {
ros::Time now() {
  if (ros::isInitialized() && ros::Time::isValid()) return ros::Time::now();
  ros::WallTime wall = ros::WallTime::now();
  return ros::Time(wall.sec, wall.nsec);
}

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

}  // namespace imagenets
