#include "imagenets/vision/marker_msgs.h"

#include <limits>

#include <boost/make_shared.hpp>

#include "imagenets/vision/frames.h"

namespace imagenets {
namespace marker {

Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return T;
}

imagenets::MarkerDetectionPtr toMsg(const Detection& d, const std::string& marker_name, const std_msgs::Header& header) {
  auto msg = boost::make_shared<imagenets::MarkerDetection>();
  msg->header = header;
  msg->marker = marker_name;
  msg->found = d.found;
  msg->confidence = d.confidence;
  msg->threshold = std::numeric_limits<double>::quiet_NaN();
  if (d.found) {
    for (const auto& p : d.points) {
      geometry_msgs::Point q;
      q.x = p.x;
      q.y = p.y;
      msg->points.push_back(q);
    }
    msg->pose = frames::toPose(d.pose);
    msg->alternative_pose = frames::toPose(d.alt_pose);
    msg->reprojection_error = d.reprojection_error;
    msg->alternative_reprojection_error = d.alt_reprojection_error;
  } else {
    msg->pose.orientation.w = msg->alternative_pose.orientation.w = 1.0;
  }
  return msg;
}

imagenets::MarkerDetectionPtr toMsg(const Detection& d, const MarkerDescription& marker, const std_msgs::Header& header) {
  auto msg = toMsg(d, marker.name, header);
  if (!d.found) return msg;
  const auto defined = marker.definedPoints();
  for (size_t i = 0; i < msg->points.size() && i < defined.size(); ++i) {
    msg->point_ids.push_back(static_cast<int>(i));
    msg->object_points.push_back(frames::toPointMsg(Eigen::Vector3d(defined[i].x, defined[i].y, defined[i].z)));
  }
  return msg;
}

imagenets::MarkerDetectionPtr toMsg(const target::TargetDetection& d, const std::string& target_name,
                                    const std_msgs::Header& header) {
  auto msg = boost::make_shared<imagenets::MarkerDetection>();
  msg->header = header;
  msg->marker = target_name;
  msg->found = d.found;
  msg->confidence = d.confidence;
  msg->threshold = std::numeric_limits<double>::quiet_NaN();
  msg->pose.orientation.w = msg->alternative_pose.orientation.w = 1.0;
  if (!d.found) return msg;
  for (size_t i = 0; i < d.points.size(); ++i) {
    geometry_msgs::Point q;
    q.x = d.points[i].x;
    q.y = d.points[i].y;
    msg->points.push_back(q);
    msg->point_ids.push_back(d.ids[i]);
    msg->object_points.push_back(frames::toPointMsg(d.object_points[i]));
  }
  msg->pose = frames::toPose(d.pose);
  msg->alternative_pose = frames::toPose(d.alt_pose);
  msg->reprojection_error = d.reprojection_error;
  msg->alternative_reprojection_error = d.alt_reprojection_error;
  return msg;
}

void shiftPoints(target::TargetDetection& d, const cv::Point2d& offset) {
  for (auto& p : d.points) p += offset;
}

void shiftPoints(Detection& d, const cv::Point2d& offset) {
  if (!d.found) return;
  for (auto& p : d.points) p += offset;
}

}  // namespace marker
}  // namespace imagenets
