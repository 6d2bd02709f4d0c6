#pragma once
#include <ros/time.h>

namespace imagenets {
// ROS time in a node; wall-clock time in a program that embeds nets without ROS.
ros::Time now();
// CPU time the calling thread has used so far, ms: what a computation costs, whatever else the
// machine does meanwhile (BlockStats::last_cpu_ms, benchmarks).
double threadCpuMs();
}  // namespace imagenets
