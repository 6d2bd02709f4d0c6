// A file shipped in a ROS package, found the ROS way (ros::package::getPath: the package in the
// workspace's source, devel or install space), never relative to another file's path.
#pragma once

#include <stdexcept>
#include <string>

#include <ros/package.h>

namespace imagenets {

// `package`'s folder + "/" + `relative`; throws naming the package when ROS does not know it.
inline std::string packageFile(const std::string& package, const std::string& relative) {
  const std::string root = ros::package::getPath(package);
  if (root.empty()) {
    throw std::runtime_error("package '" + package + "' not found (is its workspace's setup.bash sourced?)");
  }
  return root + "/" + relative;
}

}  // namespace imagenets
