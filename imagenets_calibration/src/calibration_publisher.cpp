#include "imagenets_calibration/calibration_publisher.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <visualization_msgs/MarkerArray.h>

#include "imagenets/vision/frames.h"
#include "robot_description/joint_state.h"

namespace imagenets_calibration {
namespace {

// The detected points of one image drawn on it (bgr8): the outer corners as a red outline, the
// inner points green, and a line of text saying what was found. Used for the PNG files beside the
// calibration and for the live ~detections/... images.
cv::Mat drawObservation(const sensor_msgs::ImageConstPtr& img, const MarkerObservation& o, const std::string& camera) {
  cv::Mat colour;
  cv::cvtColor(cv_bridge::toCvShare(img, "mono8")->image, colour, cv::COLOR_GRAY2BGR);
  // Line widths grow with the image so the overlay stays visible when shown scaled down (rviz).
  const int w = std::max(1, colour.cols / 400);
  for (size_t k = 0; k < o.points.size(); ++k) {
    const cv::Point2d p(o.points[k].x(), o.points[k].y());
    cv::circle(colour, p, 3 + 2 * w, k < 4 ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 200, 0), w, cv::LINE_AA);
    // The outline of the square marker or of one tag; a grid's or board's corners as dots.
    const bool outline = o.points.size() == 8 || o.points.size() == 4;
    if (k < 4 && outline) cv::line(colour, p, cv::Point2d(o.points[(k + 1) % 4].x(), o.points[(k + 1) % 4].y()),
                        cv::Scalar(0, 0, 255), w, cv::LINE_AA);
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s: %s, confidence %.2f, threshold %.0f", camera.c_str(),
                o.found ? "marker found" : "marker NOT found", o.confidence, o.threshold);
  cv::putText(colour, text, cv::Point(10, 20 + 20 * w), cv::FONT_HERSHEY_SIMPLEX, 0.5 * w, cv::Scalar(0, 255, 255), w,
              cv::LINE_AA);
  return colour;
}

}  // namespace

CalibrationPublisher::CalibrationPublisher(ros::NodeHandle nh, ros::NodeHandle pnh, const RobotModel& model,
                                           double marker_size, FusionLimits fusion, std::string child_frame,
                                           const std::string& joint_states)
    : nh_(nh), pnh_(pnh), model_(model), marker_size_(marker_size), fusion_(fusion), child_frame_(std::move(child_frame)) {
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  joint_sub_ = nh_.subscribe(joint_states, 20, &CalibrationPublisher::onJointStates, this);
}

void CalibrationPublisher::advertiseDetections(const std::vector<std::string>& cameras) {
  for (const auto& camera : cameras) detectionPublishers(camera);
}

std::pair<ros::Publisher, ros::Publisher> CalibrationPublisher::detectionPublishers(const std::string& camera) {
  std::lock_guard<std::mutex> lock(publishers_mutex_);
  auto& pubs = detection_pubs_[camera];
  if (!pubs.first) {
    pubs.first = pnh_.advertise<sensor_msgs::Image>("detections/" + camera + "/image", 1, true);
    pubs.second = pnh_.advertise<sensor_msgs::CameraInfo>("detections/" + camera + "/camera_info", 1, true);
  }
  return pubs;
}

void CalibrationPublisher::onJointStates(const sensor_msgs::JointStateConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(data_mutex_);
    if ((msg->header.stamp - last_chain_tf_).toSec() < 0.04) return;
    last_chain_tf_ = msg->header.stamp;
  }
  // Paper 4.3: the head's chain hangs from the calibrated fixed point, so the stereo camera's
  // extrinsics at the current pan/tilt are one TF lookup away.
  std::vector<double> head;
  try {
    head = robot_description::jointPositions(*msg, model_.description().head.names());
  } catch (const std::exception&) {
    return;
  }
  std::shared_ptr<const RobotModel> calibrated;
  {
    std::lock_guard<std::mutex> lock(calibration_mutex_);
    calibrated = calibrated_model_;
  }
  const RobotModel& model = calibrated ? *calibrated : model_;
  // The head's cameras in the calibrated frame, whichever of them the calibration measured with.
  const Eigen::Isometry3d left = model.headBase().inverse() * model.leftCamera(head);
  const auto& d = model_.description();
  std::vector<geometry_msgs::TransformStamped> t{
      imagenets::frames::toTransformStamped(left, child_frame_, "calibrated/" + d.left_camera.frame, msg->header.stamp),
      imagenets::frames::toTransformStamped(left * model.leftToRight(), child_frame_,
                                            "calibrated/" + d.right_camera_frame, msg->header.stamp)};
  if (!d.mono_camera.frame.empty()) {
    t.push_back(imagenets::frames::toTransformStamped(model.headBase().inverse() * model.monoCamera(head), child_frame_,
                                                      "calibrated/" + d.mono_camera.frame, msg->header.stamp));
  }
  tf_.sendTransform(t);
}

void CalibrationPublisher::publishCalibration(const Result& result) {
  const auto& base = model_.description().base_frame;
  const ros::Time now = ros::Time::now();
  std::vector<geometry_msgs::TransformStamped> t{
      imagenets::frames::toTransformStamped(result.fixed_point, base, child_frame_, now),
      imagenets::frames::toTransformStamped(model_.headBase(), base, child_frame_ + "_nominal", now)};
  static_tf_.sendTransform(t);
  auto calibrated = std::make_shared<const RobotModel>(calibratedModel(model_, result));
  std::lock_guard<std::mutex> lock(calibration_mutex_);
  calibrated_model_ = std::move(calibrated);
}

void CalibrationPublisher::publishNominal() {
  Result nominal;
  nominal.fixed_point = model_.headBase();
  publishCalibration(nominal);
}

void CalibrationPublisher::publishSampleMarkers(const Result& result) {
  // The marker pose of every sample as the calibrated chain sees it (fixed point * head chain *
  // detection): a tight cluster around the gripper marker means a consistent calibration.
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  const auto& base = model_.description().base_frame;
  std::shared_ptr<const RobotModel> calibrated;  // publishCalibration(result) made it
  {
    std::lock_guard<std::mutex> lock(calibration_mutex_);
    calibrated = calibrated_model_;
  }
  for (size_t i = 0; calibrated && i < result.samples.size(); ++i) {
    Sample s = result.samples[i];
    if (s.head_q.size() != model_.description().head.joints.size() || s.arm_q.size() != model_.description().arm.joints.size()) continue;
    solveSample(model_, s, fusion_, result.marker_offset);
    if (!s.valid) continue;
    const Eigen::Isometry3d pose = result.fixed_point * headChain(*calibrated, s.head_q) * s.marker_in_left;
    visualization_msgs::Marker m;
    m.header.frame_id = base;
    m.header.stamp = ros::Time::now();
    m.ns = "calibration_samples";
    m.id = static_cast<int>(i);
    m.type = visualization_msgs::Marker::CUBE;
    m.pose = imagenets::frames::toPose(pose);
    m.scale.x = m.scale.y = marker_size_;
    m.scale.z = 0.002;
    const bool used = std::find(result.used.begin(), result.used.end(), static_cast<int>(i)) != result.used.end();
    m.color.r = used ? 0.1f : 1.0f;
    m.color.g = used ? 0.8f : 0.2f;
    m.color.b = 0.2f;
    m.color.a = 0.6f;
    array.markers.push_back(m);
  }
  markers_pub_.publish(array);
}

void CalibrationPublisher::publishDetections(const CameraImages& images, const Sample& sample) {
  // Always drawn (a few ms), so a late subscriber of the latched topic gets the newest sample.
  for (const CameraImage& c : images) {
    try {
      const cv::Mat colour = drawObservation(c.image, observationOf(sample, c.camera), c.camera);
      const auto pubs = detectionPublishers(c.camera);
      pubs.first.publish(cv_bridge::CvImage(c.image->header, "bgr8", colour).toImageMsg());
      pubs.second.publish(c.info);
    } catch (const std::exception& e) {
      ROS_WARN("detection image of the %s camera not published: %s", c.camera.c_str(), e.what());
    }
  }
}

std::string CalibrationPublisher::savePictures(const CameraImages& images, const Sample& sample,
                                               const std::string& calibration_file) const {
  const std::string stem = calibration_file.substr(0, calibration_file.rfind('.'));
  std::string written;
  try {
    for (const CameraImage& c : images) {
      const cv::Mat colour = drawObservation(c.image, observationOf(sample, c.camera), c.camera);
      const std::string path = stem + "_" + c.camera + ".png";
      const std::string tmp = stem + ".tmp.png";
      if (!cv::imwrite(tmp, colour) || std::rename(tmp.c_str(), path.c_str()) != 0) {
        throw std::runtime_error("cannot write " + path);
      }
      written += (written.empty() ? "" : ", ") + path;
    }
  } catch (const std::exception& e) {
    ROS_WARN("pictures not saved: %s", e.what());
  }
  return written;
}

bool CalibrationPublisher::writeUrdf(const StoredCalibration& calibration, const std::string& path,
                                     std::string* note) const {
  try {
    saveCalibratedUrdf(model_, calibration, path);
    *note = "; calibrated URDF " + path;
    return true;
  } catch (const std::exception& e) {
    *note = std::string("; calibrated URDF NOT written: ") + e.what() + " (the calibration itself is saved)";
    return false;
  }
}

}  // namespace imagenets_calibration
