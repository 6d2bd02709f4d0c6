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
// gray image; throws BlockError naming the port.
render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray);
// A detector block's `confidence` (std_msgs/Float64, the feedback score) and `pose`
// (geometry_msgs/PoseStamped) outputs; nothing when the marker was not found.
void outputConfidenceAndPose(Context& ctx, const Detection& d, const std_msgs::Header& header);

}  // namespace marker
}  // namespace imagenets
