// Conversions between the marker detector's results and ROS messages.
#pragma once

#include <geometry_msgs/Pose.h>
#include <imagenets/MarkerDetection.h>

#include "imagenets/block.h"
#include "imagenets/blocks/marker.h"
#include "imagenets/blocks/render.h"

namespace imagenets {
namespace marker {

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& pose);
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);
// The detection as a message (threshold NaN: the detector does not know it).
imagenets::MarkerDetectionPtr toMsg(const Detection& d, const std::string& marker_name, const std_msgs::Header& header);
// The camera model on a detector block's input `camera_info`, checked against the size of its
// gray image; throws BlockError naming the port. A camera_info with a region of interest (`roi`,
// as ROS defines it: K is the full image's, the image is that window of it) gives the region's
// model, and `offset` (if given) is the region's corner in the full image: detectors add it to
// the points they report, so points are always full-image pixels.
render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray, cv::Point2d* offset = nullptr);
// Moves a detection's points by `offset` (from a region's pixels to the full image's).
void shiftPoints(Detection& d, const cv::Point2d& offset);
// A detector block's `confidence` (std_msgs/Float64, the feedback score) and `pose`
// (geometry_msgs/PoseStamped) outputs; nothing when the marker was not found.
void outputConfidenceAndPose(Context& ctx, const Detection& d, const std_msgs::Header& header);

}  // namespace marker
}  // namespace imagenets
