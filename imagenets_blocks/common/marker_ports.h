// The ports the marker detector blocks share: the camera model on the input `camera_info`, and the
// outputs `confidence` and `pose`.
#pragma once

#include <opencv2/core.hpp>
#include <std_msgs/Header.h>

#include "imagenets/block.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/render.h"

namespace imagenets {
namespace marker {

// The camera model on a detector block's input `camera_info`, checked against the size of its
// gray image; throws BlockError naming the port. A camera_info with a region of interest (`roi`,
// as ROS defines it: K is the full image's, the image is that window of it) gives the region's
// model, and `offset` (if given) is the region's corner in the full image: detectors add it to
// the points they report, so points are always full-image pixels.
render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray, cv::Point2d* offset = nullptr);
// The optional input `pose_hint` (T_camera_marker) into `hint`: `hint`, or nullptr without one.
const Eigen::Isometry3d* inputPoseHint(const Context& ctx, Eigen::Isometry3d* hint);
// A detector block's `confidence` (std_msgs/Float64, the feedback score) and `pose`
// (geometry_msgs/PoseStamped) outputs; nothing when the marker (or target) was not found.
void outputConfidenceAndPose(Context& ctx, bool found, double confidence, const Eigen::Isometry3d& pose,
                             const std_msgs::Header& header);
void outputConfidenceAndPose(Context& ctx, const Detection& d, const std_msgs::Header& header);
// The output `reprojection_error` (std_msgs/Float64, pixels); nothing when not found.
void outputReprojectionError(Context& ctx, bool found, double error_px);

}  // namespace marker
}  // namespace imagenets
