// friend_calibration_node: calibrates the FRIEND pan-tilt head's fixed point on request.
//
// It drives the arm and the head through their actionlib servers (imagenets/MoveJoints), takes a
// stereo pair per sample, detects the gripper marker robustly in both images in parallel, and
// solves the calibration with the library (calibration.h) — the same chain as the Fig. 4.2 / 4.3
// nets, embedded as C++ so that a sample costs no net-loading or message-copy overhead and the
// raw data of every sample is at hand for storage and replay.
//
// Interfaces (in the node's private namespace, e.g. /friend_calibration/...):
//   ~calibrate          service imagenets/Calibrate
//   ~calibrate_action   action imagenets/Calibrate (feedback: sample k of N; cancellable)
//   tf_static           base_frame -> pth_fixed_point (calibrated), base_frame ->
//                       pth_fixed_point_nominal; tf: pth_fixed_point -> calibrated stereo optical
//                       frames at the current pan/tilt (paper 4.3: extrinsics from TF)
//   ~markers            visualization_msgs/MarkerArray: marker poses of all samples (latched)
//   ~detections/{left,right}/image   bgr8, the detected marker points drawn, per sample as it is
//                       measured (latched), with ~detections/{left,right}/camera_info beside it
// Parameters (private): description, marker, calibration_file, redundancy (5), method (joint),
//   arm_action, head_action, server_timeout (s, 10: the action servers at each calibration's start),
//   joint_states, stereo_namespace, camera_timeout (s), motion_timeout (s), speed_scale, settle_time (s), reapproach (bool), poses_per_loop (joint method, 2), fusion/max_position_difference (m),
//   fusion/max_angle_difference (rad), min_valid_fraction, replay (file re-solved at start-up),
//   trigger_service (std_srvs/Trigger called after each motion; default stereo/trigger).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/client/simple_action_client.h>
#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "friend_calibration/calibration.h"
#include "friend_calibration/calibration_marker_net.h"
#include "imagenets/vision/marker.h"
#include "friend_calibration/storage.h"
#include "imagenets/Calibrate.h"
#include "imagenets/CalibrateAction.h"
#include "imagenets/MoveJointsAction.h"
#include "imagenets/calling_thread_queue.h"

namespace friend_calibration {

class CalibrationNode {
 public:
  CalibrationNode(ros::NodeHandle nh, ros::NodeHandle pnh);

  // Feedback (sample, of, stage) and cancellation hooks of one run.
  struct Hooks {
    std::function<void(int, int, const std::string&)> progress;
    std::function<bool()> cancelled;
  };
  // One calibration (robot or replay). Never throws: failures come back with success = false.
  imagenets::Calibrate::Response run(const imagenets::Calibrate::Request& req, const Hooks& hooks);

 private:
  using MoveClient = actionlib::SimpleActionClient<imagenets::MoveJointsAction>;
  // The arm and head clients of one calibration, called back only in its thread's waits
  // (imagenets/calling_thread_queue.h says why they are not kept for the node's life).
  struct Motion {
    Motion(const ros::NodeHandle& nh, const std::string& arm_action, const std::string& head_action)
        : queue(nh), arm(queue.nodeHandle(), arm_action, false), head(queue.nodeHandle(), head_action, false) {}
    imagenets::CallingThreadQueue queue;
    MoveClient arm, head;
  };
  struct StereoPair {
    sensor_msgs::ImageConstPtr left, right;
    sensor_msgs::CameraInfoConstPtr left_info, right_info;
  };

  bool onService(imagenets::Calibrate::Request& req, imagenets::Calibrate::Response& res);
  void onAction(const imagenets::CalibrateGoalConstPtr& goal);
  void onJointStates(const sensor_msgs::JointStateConstPtr& msg);
  void onImage(const sensor_msgs::ImageConstPtr& msg, bool left);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg, bool left);

  // Samples on the robot; throws std::runtime_error with the failure's description.
  std::vector<Sample> collectSamples(int n, const std::string& method, const Hooks& hooks);
  void moveBoth(Motion& motion, const CalibrationPose& pose, int sample, const Hooks& hooks);
  StereoPair waitForStereoPair(const ros::Time& after, const Hooks& hooks);
  sensor_msgs::JointStateConstPtr waitForJointStates(const ros::Time& after);
  Sample measure(const StereoPair& pair, const sensor_msgs::JointState& joints);
  void publish(const Result& result, const std::string& frame);
  std::string savePictures(const Sample& sample);
  void publishDetections(const StereoPair& pair, const Sample& sample);
  void publishSampleMarkers(const Result& result);

  ros::NodeHandle nh_, pnh_;
  RobotModel model_;
  imagenets::marker::MarkerDescription marker_;
  std::string calibration_file_, child_frame_ = "pth_fixed_point";
  int default_redundancy_ = 5;
  std::string default_method_ = "joint";
  double server_timeout_ = 10.0, camera_timeout_ = 3.0, motion_timeout_ = 60.0, speed_scale_ = 1.0, settle_time_ = 0.0;
  bool reapproach_ = true;
  int poses_per_loop_ = 2;
  double min_valid_fraction_ = 0.5;
  FusionLimits fusion_;
  CombineOptions combine_;
  // The robust detection net (config/nets/calibration_marker_detection.yaml), one per camera so
  // the left and right image are measured in parallel.
  std::unique_ptr<CalibrationMarkerNet> detection_nets_[2];

  std::string arm_action_, head_action_;
  ros::Subscriber joint_sub_, image_sub_[2], info_sub_[2];
  ros::ServiceServer service_;
  ros::ServiceClient trigger_;
  std::unique_ptr<actionlib::SimpleActionServer<imagenets::CalibrateAction>> action_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher markers_pub_, detection_image_pub_[2], detection_info_pub_[2];

  std::mutex data_mutex_;  // guards the latest sensor data below
  sensor_msgs::JointStateConstPtr joints_;
  std::vector<sensor_msgs::ImageConstPtr> images_[2];  // a few recent images per camera
  sensor_msgs::CameraInfoConstPtr infos_[2];
  StereoPair last_pair_;
  ros::Time last_chain_tf_;

  std::mutex calibration_mutex_;  // guards current_ (the published calibration)
  bool have_calibration_ = false;
  Eigen::Isometry3d current_ = Eigen::Isometry3d::Identity();
  std::mutex busy_mutex_;  // guards busy_with_, and busy_ being set
  std::atomic<bool> busy_{false};
  double detection_time_ = 0;  // s, robust detection of the running calibration (both images)
  std::string busy_with_;
};

}  // namespace friend_calibration
