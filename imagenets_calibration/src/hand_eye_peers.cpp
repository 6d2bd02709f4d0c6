#include "imagenets_calibration/hand_eye_peers.h"

#include <Eigen/SVD>
#include <opencv2/calib3d.hpp>

namespace imagenets_calibration {

namespace {

cv::Mat rotationOf(const Eigen::Isometry3d& t) {
  cv::Mat r(3, 3, CV_64F);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.at<double>(i, j) = t.linear()(i, j);
  return r;
}
cv::Mat translationOf(const Eigen::Isometry3d& t) {
  cv::Mat v(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) v.at<double>(i) = t.translation()(i);
  return v;
}
Eigen::Isometry3d isometryOf(const cv::Mat& r, const cv::Mat& t) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  cv::Mat rd, td;
  r.convertTo(rd, CV_64F);
  t.convertTo(td, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) out.linear()(i, j) = rd.at<double>(i, j);
    out.translation()(i) = td.at<double>(i);
  }
  return out;
}

// T_tcp_target from a camera pose: the mean over the samples (rotation: the chordal mean).
Eigen::Isometry3d targetOffset(const std::vector<HandEyeSample>& samples, const Eigen::Isometry3d& base_camera) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (const auto& s : samples) {
    const Eigen::Isometry3d m = s.base_tcp.inverse() * base_camera * s.camera_target;
    sum += m.rotation();
    t += m.translation() / static_cast<double>(samples.size());
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d r = svd.matrixU() * svd.matrixV().transpose();
  if (r.determinant() < 0) {
    Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
    d(2, 2) = -1;
    r = svd.matrixU() * d * svd.matrixV().transpose();
  }
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = r;
  out.translation() = t;
  return out;
}

}  // namespace

std::vector<HandEyeSolution> eyeToHandPeers(const std::vector<HandEyeSample>& samples) {
  std::vector<HandEyeSolution> out;
  // calibrateHandEye, eye-to-hand: the gripper poses inverted (T_tcp_base as "gripper2base"), the
  // target in the camera as it is; "cam2gripper" is then T_base_camera.
  std::vector<cv::Mat> r_tcp_base, t_tcp_base, r_cam_target, t_cam_target, r_base_tcp, t_base_tcp;
  for (const auto& s : samples) {
    const Eigen::Isometry3d inv = s.base_tcp.inverse();
    r_tcp_base.push_back(rotationOf(inv));
    t_tcp_base.push_back(translationOf(inv));
    r_cam_target.push_back(rotationOf(s.camera_target));
    t_cam_target.push_back(translationOf(s.camera_target));
    r_base_tcp.push_back(rotationOf(s.base_tcp));
    t_base_tcp.push_back(translationOf(s.base_tcp));
  }
  const std::vector<std::pair<const char*, cv::HandEyeCalibrationMethod>> hand_eye{
      {"Tsai", cv::CALIB_HAND_EYE_TSAI},       {"Park", cv::CALIB_HAND_EYE_PARK},
      {"Horaud", cv::CALIB_HAND_EYE_HORAUD},   {"Andreff", cv::CALIB_HAND_EYE_ANDREFF},
      {"Daniilidis", cv::CALIB_HAND_EYE_DANIILIDIS}};
  for (const auto& [name, method] : hand_eye) {
    HandEyeSolution s;
    s.method = name;
    try {
      cv::Mat r, t;
      cv::calibrateHandEye(r_tcp_base, t_tcp_base, r_cam_target, t_cam_target, r, t, method);
      s.base_camera = isometryOf(r, t);
      s.tcp_target = targetOffset(samples, s.base_camera);
      s.ok = s.base_camera.matrix().allFinite();
    } catch (const cv::Exception& e) {
      s.error = e.what();
    }
    out.push_back(s);
  }
  // calibrateRobotWorldHandEye solves A X = Z B. Here T_camera_target T_target_tcp = T_camera_base
  // T_base_tcp: A = T_camera_target ("world2cam"), B = T_base_tcp ("base2gripper"), so X
  // ("base2world") is T_target_tcp and Z ("gripper2cam") is T_camera_base.
  const std::vector<std::pair<const char*, cv::RobotWorldHandEyeCalibrationMethod>> robot_world{
      {"Shah", cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH}, {"Li", cv::CALIB_ROBOT_WORLD_HAND_EYE_LI}};
  for (const auto& [name, method] : robot_world) {
    HandEyeSolution s;
    s.method = name;
    try {
      cv::Mat rx, tx, rz, tz;
      cv::calibrateRobotWorldHandEye(r_cam_target, t_cam_target, r_base_tcp, t_base_tcp, rx, tx, rz, tz, method);
      s.tcp_target = isometryOf(rx, tx).inverse();
      s.base_camera = isometryOf(rz, tz).inverse();
      s.ok = s.base_camera.matrix().allFinite() && s.tcp_target.matrix().allFinite();
    } catch (const cv::Exception& e) {
      s.error = e.what();
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace imagenets_calibration
