#include "imagenets_calibration/calibration_msgs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "imagenets/vision/frames.h"

namespace imagenets_calibration {
namespace frames = imagenets::frames;

MarkerObservation observationOf(const imagenets::MarkerDetection* detection, const imagenets::FeedbackTrace* trace,
                                const std::string& why_not) {
  MarkerObservation o;
  if (!detection || !detection->found) {
    o.reason = why_not;
    return o;
  }
  o.found = true;
  o.confidence = detection->confidence;
  o.threshold = trace ? trace->chosen_value : std::numeric_limits<double>::quiet_NaN();
  o.reprojection_error = detection->reprojection_error;
  o.pose = frames::toIsometry(detection->pose, "detection pose");
  for (const auto& p : detection->points) o.points.emplace_back(p.x, p.y);
  o.point_ids.assign(detection->point_ids.begin(), detection->point_ids.end());
  for (const auto& p : detection->object_points) o.object_points.emplace_back(p.x, p.y, p.z);
  return o;
}

imagenets_calibration_msgs::MarkerObservation toMsg(const MarkerObservation& o) {
  imagenets_calibration_msgs::MarkerObservation m;
  m.found = o.found;
  m.pose = frames::toPose(o.pose);
  m.confidence = o.confidence;
  m.threshold = o.threshold;
  m.reprojection_error = o.reprojection_error;
  for (const auto& p : o.points) m.points.push_back(frames::toPointMsg(Eigen::Vector3d(p.x(), p.y(), 0)));
  m.point_ids.assign(o.point_ids.begin(), o.point_ids.end());
  for (const auto& p : o.object_points) m.object_points.push_back(frames::toPointMsg(p));
  m.reason = o.reason;
  return m;
}

MarkerObservation fromMsg(const imagenets_calibration_msgs::MarkerObservation& m) {
  MarkerObservation o;
  o.found = m.found;
  // A camera the sample was not measured with leaves its observation unset (all zero): no pose.
  if (m.found) o.pose = frames::toIsometry(m.pose, "marker observation pose");
  o.confidence = m.confidence;
  o.threshold = m.threshold;
  o.reprojection_error = m.reprojection_error;
  for (const auto& p : m.points) o.points.emplace_back(p.x, p.y);
  o.point_ids.assign(m.point_ids.begin(), m.point_ids.end());
  for (const auto& p : m.object_points) o.object_points.emplace_back(p.x, p.y, p.z);
  o.reason = m.reason;
  return o;
}

imagenets_calibration_msgs::CalibrationSample toMsg(const Sample& s) {
  imagenets_calibration_msgs::CalibrationSample m;
  m.stamp = s.stamp;
  m.arm_q = s.arm_q;
  m.head_q = s.head_q;
  m.left = toMsg(s.left);
  m.right = toMsg(s.right);
  m.mono = toMsg(s.mono);
  m.valid = s.valid;
  m.reason = s.reason;
  m.fusion = s.fusion;
  m.marker_in_left = frames::toPose(s.marker_in_left);
  m.fixed_point = frames::toPose(s.fixed_point);
  return m;
}

Sample fromMsg(const imagenets_calibration_msgs::CalibrationSample& m) {
  Sample s;
  s.stamp = m.stamp;
  s.arm_q = m.arm_q;
  s.head_q = m.head_q;
  s.left = fromMsg(m.left);
  s.right = fromMsg(m.right);
  s.mono = fromMsg(m.mono);
  s.valid = m.valid;
  s.reason = m.reason;
  s.fusion = m.fusion;
  s.marker_in_left = frames::toIsometry(m.marker_in_left, "sample marker_in_left");
  s.fixed_point = frames::toIsometry(m.fixed_point, "sample fixed_point");
  return s;
}

imagenets_calibration_msgs::CalibrationResult toMsg(const Result& r, const std::string& base, const std::string& child) {
  imagenets_calibration_msgs::CalibrationResult m;
  m.success = r.success;
  m.message = r.message;
  m.method = r.method;
  m.fixed_point = frames::toTransformStamped(r.fixed_point, base, child, ros::Time());
  m.marker_offset = frames::toPose(r.marker_offset);
  m.arm_joint_offsets = r.arm_joint_offsets;
  m.head_joint_offsets = r.head_joint_offsets;
  m.std_dev_translation = frames::toVector3Msg(r.std_translation);
  m.std_dev_rotation = frames::toVector3Msg(r.std_rotation);
  m.used = r.used;
  m.rejected = r.rejected;
  m.rejection_reasons = r.rejection_reasons;
  m.residual_translation = r.residual_translation;
  m.residual_rotation = r.residual_rotation;
  m.compute_time = r.compute_time;
  // Symmetric: row- and column-major are the same.
  std::copy(r.fixed_point_covariance.data(), r.fixed_point_covariance.data() + 36, m.fixed_point_covariance.begin());
  std::copy(r.marker_offset_covariance.data(), r.marker_offset_covariance.data() + 36, m.marker_offset_covariance.begin());
  m.arm_joint_offset_std = r.arm_joint_offset_std;
  m.head_joint_offset_std = r.head_joint_offset_std;
  m.reprojection_rms = r.reprojection_rms;
  m.unobservable = r.unobservable;
  m.condition_number = r.condition_number;
  for (const auto& s : r.samples) m.samples.push_back(toMsg(s));
  return m;
}

Result fromMsg(const imagenets_calibration_msgs::CalibrationResult& m) {
  Result r;
  r.success = m.success;
  r.message = m.message;
  r.method = m.method;
  r.fixed_point = frames::toIsometry(m.fixed_point.transform, "result fixed_point");
  r.marker_offset = frames::toIsometry(m.marker_offset, "result marker_offset");
  r.arm_joint_offsets = m.arm_joint_offsets;
  r.head_joint_offsets = m.head_joint_offsets;
  r.std_translation = frames::toVector(m.std_dev_translation, "std_dev_translation");
  r.std_rotation = frames::toVector(m.std_dev_rotation, "std_dev_rotation");
  r.used = m.used;
  r.rejected = m.rejected;
  r.rejection_reasons = m.rejection_reasons;
  r.residual_translation = m.residual_translation;
  r.residual_rotation = m.residual_rotation;
  r.compute_time = m.compute_time;
  r.fixed_point_covariance = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(m.fixed_point_covariance.data());
  r.marker_offset_covariance = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(m.marker_offset_covariance.data());
  r.has_covariance = r.fixed_point_covariance.trace() > 0;
  r.arm_joint_offset_std = m.arm_joint_offset_std;
  r.head_joint_offset_std = m.head_joint_offset_std;
  r.reprojection_rms = m.reprojection_rms;
  r.unobservable = m.unobservable;
  r.condition_number = m.condition_number;
  for (const auto& s : m.samples) r.samples.push_back(fromMsg(s));
  return r;
}

void summarize(const imagenets_calibration_msgs::CalibrationResult& m, imagenets_calibration_msgs::Calibrate::Response& out) {
  out.success = m.success;
  out.message = m.message;
  out.fixed_point = m.fixed_point;
  out.std_dev_translation = m.std_dev_translation;
  out.std_dev_rotation = m.std_dev_rotation;
  out.fixed_point_covariance = m.fixed_point_covariance;
  out.samples_used = static_cast<int>(m.used.size());
  out.samples_rejected = static_cast<int>(m.rejected.size());
  out.rejected_samples = m.rejected;
  out.residual_translation = m.residual_translation;
  out.residual_rotation = m.residual_rotation;
  out.compute_time = m.compute_time;
  out.unobservable = m.unobservable;
  out.condition_number = m.condition_number;
  out.poses_taken = static_cast<int>(m.samples.size());
  for (int i = 0; i < 6; ++i) {
    out.fixed_point_std_dev[i] = std::sqrt(m.fixed_point_covariance[7 * i]);
    out.marker_offset_std_dev[i] = std::sqrt(m.marker_offset_covariance[7 * i]);
  }
  out.arm_joint_offset_std = m.arm_joint_offset_std;
  out.head_joint_offset_std = m.head_joint_offset_std;
}

}  // namespace imagenets_calibration
