// Conversions between the marker detector's results and ROS messages.
#pragma once

#include <string>

#include <geometry_msgs/Pose.h>
#include <imagenets/MarkerDetection.h>
#include <std_msgs/Header.h>

#include "imagenets/vision/marker.h"
#include "imagenets/vision/target.h"

namespace imagenets {
namespace marker {

// The pose in a message as an isometry, its quaternion normalised (no checks: the detector's own
// poses; frames::toIsometry checks a pose from outside).
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);
// The detection as a message (threshold NaN: the detector does not know it).
imagenets::MarkerDetectionPtr toMsg(const Detection& d, const std::string& marker_name, const std_msgs::Header& header);
// The same with the points' ids (0..7) and their place on the marker (its 8 defined points).
imagenets::MarkerDetectionPtr toMsg(const Detection& d, const MarkerDescription& marker, const std_msgs::Header& header);
// A target detection (target.h): every corner found with its id and its point on the target.
imagenets::MarkerDetectionPtr toMsg(const target::TargetDetection& d, const std::string& target_name,
                                    const std_msgs::Header& header);
// Moves a detection's points by `offset` (from a region's pixels to the full image's).
void shiftPoints(Detection& d, const cv::Point2d& offset);
void shiftPoints(target::TargetDetection& d, const cv::Point2d& offset);

}  // namespace marker
}  // namespace imagenets
