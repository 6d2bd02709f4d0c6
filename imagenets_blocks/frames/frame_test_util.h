// Message builders for the frames block tests.
#pragma once

#include <cmath>

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/TransformStamped.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/vision/frames.h"

namespace imagenets {
namespace blocks {
namespace test {

inline Eigen::Isometry3d isometry(double x, double y, double z, double angle = 0,
                                  const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

inline geometry_msgs::TransformStamped::Ptr frame(const Eigen::Isometry3d& t, const std::string& parent,
                                                  const std::string& child) {
  geometry_msgs::TransformStamped::Ptr m(new geometry_msgs::TransformStamped);
  m->header.frame_id = parent;
  m->child_frame_id = child;
  m->transform = frames::toTransform(t);
  return m;
}

inline Eigen::Isometry3d toEigen(const geometry_msgs::TransformStamped& m) {
  return frames::toIsometry(m.transform, "output");
}

}  // namespace test
}  // namespace blocks
}  // namespace imagenets
