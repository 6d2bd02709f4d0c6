// What the calibration node shows and writes of a calibration, apart from running it:
//   tf_static   base_frame -> <child frame> (calibrated) and -> <child frame>_nominal
//   tf          <child frame> -> calibrated/<camera optical frames> at the head's current joint
//               readings (paper 4.3: extrinsics from TF), from `joint_states`
//   ~markers    visualization_msgs/MarkerArray: the target pose of every sample (latched)
//   ~detections/<camera>/image, .../camera_info   bgr8, the detected points drawn, per sample
//               (latched)
//   files       the last sample's images with the detection drawn, and the calibrated URDF
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/calibration_net_interface.h"
#include "imagenets_calibration/storage.h"

namespace imagenets_calibration {

class CalibrationPublisher {
 public:
  // `marker_size`: the drawn samples' size, m; `child_frame`: the calibrated frame (pth_fixed_point).
  CalibrationPublisher(ros::NodeHandle nh, ros::NodeHandle pnh, const RobotModel& model, double marker_size,
                       FusionLimits fusion, std::string child_frame, const std::string& joint_states);

  // Advertises the detection topics of these cameras now, so subscribers are connected before the
  // first sample (others are advertised when first needed).
  void advertiseDetections(const std::vector<std::string>& cameras);
  // The calibrated frame on tf_static; the cameras' TF follows its calibrated model from now on.
  void publishCalibration(const Result& result);
  // The nominal frame (no calibration yet).
  void publishNominal();
  // After publishCalibration(result): every sample's target pose as the calibrated chain sees it.
  void publishSampleMarkers(const Result& result);
  // One sample's images with its detections drawn.
  void publishDetections(const CameraImages& images, const Sample& sample);
  // The images with the detections drawn as <stem>_<camera>.png beside `calibration_file`; the
  // files written ("" if none: a failure is logged, not thrown).
  std::string savePictures(const CameraImages& images, const Sample& sample, const std::string& calibration_file) const;
  // The calibrated URDF at `path`; false when it could not be written. `note`: what happened, for
  // the response's message.
  bool writeUrdf(const StoredCalibration& calibration, const std::string& path, std::string* note) const;

 private:
  void onJointStates(const sensor_msgs::JointStateConstPtr& msg);
  // The latched detection topics of `camera`, advertised when first needed.
  std::pair<ros::Publisher, ros::Publisher> detectionPublishers(const std::string& camera);

  ros::NodeHandle nh_, pnh_;
  const RobotModel& model_;
  const double marker_size_;
  const FusionLimits fusion_;
  const std::string child_frame_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher markers_pub_;
  ros::Subscriber joint_sub_;
  std::mutex publishers_mutex_;
  std::map<std::string, std::pair<ros::Publisher, ros::Publisher>> detection_pubs_;  // camera -> image, info

  std::mutex data_mutex_;  // guards last_chain_tf_
  ros::Time last_chain_tf_;
  std::mutex calibration_mutex_;  // guards calibrated_model_
  // The robot as calibrated (estimated joint zero offsets, e.g. the head's tilt): the head chain
  // of the calibrated camera frames.
  std::shared_ptr<const RobotModel> calibrated_model_;
};

}  // namespace imagenets_calibration
