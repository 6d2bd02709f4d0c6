// friend_calibration_node: calibrates the FRIEND pan-tilt head's fixed point on request.
//
// It runs the calibration net (config/nets/calibration.yaml, the one definition of the method that
// roslaunch and `imagenets run` also run: plan -> the sample net repeated once per sample (move
// arm and head, stereo pair, the robust detection net in both images in parallel) -> solve)
// through imagenets::Executor, loaded once; a replay runs the same net with the replay sample net
// (calibration_sample_replay.yaml: sample k of a saved file) in place of the acquisition. The
// node adds the ROS interface: service, action (feedback and cancel from the executor's run
// events and cancel), storage, tf2, the detection images and rviz markers.
//
// Interfaces (in the node's private namespace, e.g. /calibration/...):
//   ~calibrate          service imagenets_calibration_msgs/Calibrate
//   ~calibrate_action   action imagenets_calibration_msgs/Calibrate (feedback: sample k of N and the block of the
//                       sample net that started, and with an uncertainty target the bounds after
//                       each pose added; cancellable)
//   tf_static           base_frame -> pth_fixed_point (calibrated), base_frame ->
//                       pth_fixed_point_nominal; tf: pth_fixed_point -> calibrated stereo optical
//                       frames at the current pan/tilt (paper 4.3: extrinsics from TF)
//   ~markers            visualization_msgs/MarkerArray: marker poses of all samples (latched)
//   ~detections/{left,right}/image   bgr8, the detected marker points drawn, per sample as it is
//                       measured (latched), with ~detections/{left,right}/camera_info beside it
// Parameters (private): net (the calibration net file), replay_net (the sample net of replays),
//   description, marker, calibration_file, redundancy (5), method (joint), poses_per_loop (joint
//   method, 2), max_poses (with an uncertainty target and no request max_poses: at most this many
//   poses; 30), fusion/max_position_difference (m), fusion/max_angle_difference (rad),
//   min_valid_fraction, urdf_file (the calibrated URDF written after each saved calibration;
//   default beside calibration_file, .urdf), max_uncertainty (m, 3-sigma translation bound above which a calibration
//   does not replace a good saved one; 0.002, 0 = off), replay (file re-solved at start-up),
//   joint_states, record_bag (a rosbag to record each live calibration's samples in: per sample the
//   stereo pair, both camera_info and the joint readings it used, and tf / tf_static while it runs;
//   written whole on success, a failed run leaves the previous bag as it was: bag_recorder.h),
//   record_camera (the camera namespace the bag names, "stereo"). The acquisition's
//   settings (speed, timeouts, settling, camera namespace) are properties of the sample net's
//   blocks: use ~net for a net with other values.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_broadcaster.h>

#include "imagenets_calibration/bag_recorder.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets/vision/marker.h"
#include "imagenets_calibration/storage.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets_calibration_msgs/CalibrateAction.h"
#include "imagenets/executor.h"

namespace imagenets_calibration {

class CalibrationNode {
 public:
  CalibrationNode(ros::NodeHandle nh, ros::NodeHandle pnh);

  // Feedback of one run (sample k of N, stage; the bounds reached after a pose added for a target).
  using Progress = std::function<void(const imagenets_calibration_msgs::CalibrateFeedback&)>;
  // One calibration (robot or replay). Never throws: failures come back with success = false.
  imagenets_calibration_msgs::Calibrate::Response run(const imagenets_calibration_msgs::Calibrate::Request& req, const Progress& progress);
  // Stops the running calibration (thread-safe; a no-op when none runs).
  void cancel();

 private:
  struct StereoPair {
    sensor_msgs::ImageConstPtr left, right;
    sensor_msgs::CameraInfoConstPtr left_info, right_info;
  };

  bool onService(imagenets_calibration_msgs::Calibrate::Request& req, imagenets_calibration_msgs::Calibrate::Response& res);
  void onAction(const imagenets_calibration_msgs::CalibrateGoalConstPtr& goal);
  void onJointStates(const sensor_msgs::JointStateConstPtr& msg);
  void onTf(const tf2_msgs::TFMessageConstPtr& msg, bool is_static);
  // One sample into the bag being recorded (none: nothing).
  void record(const StereoPair& pair, const Sample& sample);

  // Loads ~net (and its replay twin); throws naming the file, block or port that is wrong.
  void loadNets(const std::string& net, const std::string& replay_net);
  // The marker detection's time over all poses, s: per pose the larger of the two images' (they
  // are detected in parallel), as wall time and as the detecting threads' CPU time.
  struct DetectionTime {
    double wall = 0, cpu = 0;
  };
  // Runs `exec` (the live or the replay net) and returns its result; throws with the failure.
  // `samples`: N for the feedback (0: unknown; with a target the maximum); fills the last stereo
  // pair and the detection time.
  // `requested`: the poses taken in any case (with a target, each one after them is fed back with
  // the bounds reached).
  Result runNet(imagenets::Executor& exec, const Progress& progress, int samples, int requested, StereoPair* last_pair,
                DetectionTime* detection_time);
  // The until net of the net's sample sub-net (calibration_target.yaml), or null.
  static imagenets::Executor* untilNet(const imagenets::Executor& exec);
  void publish(const Result& result, const std::string& frame);
  std::string savePictures(const StereoPair& pair, const Sample& sample);
  void publishDetections(const StereoPair& pair, const Sample& sample);
  void publishSampleMarkers(const Result& result);  // after publish(result): its calibrated model

  ros::NodeHandle nh_, pnh_;
  RobotModel model_;
  imagenets::marker::MarkerDescription marker_;
  std::string calibration_file_, child_frame_ = "pth_fixed_point";
  std::string urdf_file_;  // the calibrated URDF written beside the calibration (storage.h)
  int default_redundancy_ = 5;
  std::string default_method_ = "joint";
  int poses_per_loop_ = 2;
  int max_poses_ = 30;
  double min_valid_fraction_ = 0.5;
  FusionLimits fusion_;

  // The calibration net, loaded once, and the same net with the replay sample net.
  std::string net_file_;
  std::unique_ptr<imagenets::Executor> live_, replay_;
  std::string net_error_;  // why the nets did not load ("" when they did)
  std::atomic<imagenets::Executor*> running_{nullptr};

  ros::Subscriber joint_sub_;
  ros::ServiceServer service_;
  std::unique_ptr<actionlib::SimpleActionServer<imagenets_calibration_msgs::CalibrateAction>> action_;
  std::mutex feedback_mutex_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  tf2_ros::TransformBroadcaster tf_;
  ros::Publisher markers_pub_, detection_image_pub_[2], detection_info_pub_[2];

  // ~record_bag: the recording of the running calibration (null when none), the topics it names
  // and the static transforms so far (written at each recording's start: they are latched).
  std::string record_bag_, record_camera_topic_, record_joint_states_topic_;
  std::mutex recorder_mutex_;  // guards recorder_ and tf_static_
  std::shared_ptr<BagRecorder> recorder_;
  std::map<std::string, geometry_msgs::TransformStamped> tf_static_;
  ros::Subscriber tf_sub_, tf_static_sub_;

  std::mutex data_mutex_;  // guards last_chain_tf_
  ros::Time last_chain_tf_;

  std::mutex calibration_mutex_;  // guards current_ and calibrated_model_ (the published calibration)
  bool have_calibration_ = false;
  Eigen::Isometry3d current_ = Eigen::Isometry3d::Identity();
  // The robot as calibrated (estimated joint zero offsets, e.g. the head's tilt): the head chain
  // of the calibrated camera frames.
  std::shared_ptr<const RobotModel> calibrated_model_;
  std::mutex busy_mutex_;  // guards busy_with_, and busy_ being set
  std::atomic<bool> busy_{false};
  std::string busy_with_;
};

}  // namespace imagenets_calibration
