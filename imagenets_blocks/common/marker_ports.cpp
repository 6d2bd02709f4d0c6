#include "marker_ports.h"

#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "camera_ports.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/marker_msgs.h"

namespace imagenets {
namespace marker {

render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray, cv::Point2d* offset) {
  render::CameraModel camera = blocks::inputCameraModel(ctx, "camera_info");
  const auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
  const sensor_msgs::RegionOfInterest& roi = info->roi;
  if (roi.width > 0 && roi.height > 0) {
    const cv::Rect region(roi.x_offset, roi.y_offset, roi.width, roi.height);
    if ((region & cv::Rect(0, 0, camera.width, camera.height)) != region) {
      throw BlockError("input 'camera_info': roi " + std::to_string(roi.width) + "x" + std::to_string(roi.height) +
                       " at " + std::to_string(roi.x_offset) + "," + std::to_string(roi.y_offset) +
                       " is not inside the " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                       " image");
    }
    camera = camera.cropped(region);
    if (offset) *offset = cv::Point2d(roi.x_offset, roi.y_offset);
  } else if (offset) {
    *offset = cv::Point2d(0, 0);
  }
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw BlockError("input 'gray': image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                     " but camera_info is " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                     (roi.width > 0 && roi.height > 0 ? " (its roi)" : ""));
  }
  return camera;
}

const Eigen::Isometry3d* inputPoseHint(const Context& ctx, Eigen::Isometry3d* hint) {
  const auto pose_hint = ctx.input<geometry_msgs::PoseStamped>("pose_hint");
  if (!pose_hint) return nullptr;
  *hint = fromPoseMsg(pose_hint->pose);
  return hint;
}

void outputConfidenceAndPose(Context& ctx, bool found, double confidence, const Eigen::Isometry3d& pose,
                             const std_msgs::Header& header) {
  if (!found) return;
  auto score = boost::make_shared<std_msgs::Float64>();
  score->data = confidence;
  ctx.output("confidence", score);
  auto msg = boost::make_shared<geometry_msgs::PoseStamped>();
  msg->header = header;
  msg->pose = frames::toPose(pose);
  ctx.output("pose", msg);
}

void outputConfidenceAndPose(Context& ctx, const Detection& d, const std_msgs::Header& header) {
  outputConfidenceAndPose(ctx, d.found, d.confidence, d.pose, header);
}

void outputReprojectionError(Context& ctx, bool found, double error_px) {
  if (!found) return;
  auto error = boost::make_shared<std_msgs::Float64>();
  error->data = error_px;
  ctx.output("reprojection_error", error);
}

}  // namespace marker
}  // namespace imagenets
