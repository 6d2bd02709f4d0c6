// Reading frames from ports with errors that name the port (private to the frames blocks).
#pragma once

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/TransformStamped.h>

#include "imagenets/block.h"
#include "imagenets/vision/frames.h"

namespace imagenets {
namespace blocks {

// The input frame as an isometry; BlockError naming the port if missing, NaN or non-unit.
inline Eigen::Isometry3d inputFrame(const Context& ctx, const std::string& port,
                                    geometry_msgs::TransformStamped::ConstPtr* msg_out = nullptr) {
  auto msg = ctx.input<geometry_msgs::TransformStamped>(port);
  if (!msg) throw BlockError("input '" + port + "': no frame");
  if (msg_out) *msg_out = msg;
  try {
    return frames::toIsometry(msg->transform, "input '" + port + "'");
  } catch (const frames::FrameError& e) {
    throw BlockError(e.what());
  }
}

// Every pose of a PoseArray input; BlockError if missing, empty, or one pose is bad.
inline std::vector<Eigen::Isometry3d> inputPoses(const Context& ctx, const std::string& port,
                                                 geometry_msgs::PoseArray::ConstPtr* msg_out = nullptr) {
  auto msg = ctx.input<geometry_msgs::PoseArray>(port);
  if (!msg) throw BlockError("input '" + port + "': no poses");
  if (msg->poses.empty()) throw BlockError("input '" + port + "': empty pose array");
  if (msg_out) *msg_out = msg;
  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(msg->poses.size());
  try {
    for (size_t i = 0; i < msg->poses.size(); ++i) {
      poses.push_back(frames::toIsometry(msg->poses[i], "input '" + port + "' pose " + std::to_string(i)));
    }
  } catch (const frames::FrameError& e) {
    throw BlockError(e.what());
  }
  return poses;
}

inline geometry_msgs::TransformStamped::Ptr frameMsg(const Eigen::Isometry3d& t, const std_msgs::Header& header,
                                                     const std::string& child_frame_id) {
  geometry_msgs::TransformStamped::Ptr msg(new geometry_msgs::TransformStamped);
  msg->header = header;
  msg->child_frame_id = child_frame_id;
  msg->transform = frames::toTransform(t);
  return msg;
}

}  // namespace blocks
}  // namespace imagenets
