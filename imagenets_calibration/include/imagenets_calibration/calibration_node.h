// friend_calibration_node: calibrates the FRIEND pan-tilt head's fixed point on request.
//
// It runs the calibration net (config/nets/calibration.yaml, the one definition of the method that
// roslaunch and `imagenets run` also run: plan -> the sample net repeated once per sample (move
// arm and head, stereo pair, the robust detection net in both images in parallel) -> solve)
// through imagenets::Executor, loaded once; a replay runs the same net with the replay sample net
// (calibration_sample_replay.yaml: sample k of a saved file) in place of the acquisition. The
// node adds the ROS interface: service, action (feedback and cancel from the executor's run
// events and cancel), storage and the recording; what it shows (tf2, the detection images, rviz
// markers, pictures, the URDF) is CalibrationPublisher's. It reads of its net only what
// calibration_net_interface.h lists, so a net of one's own (~net) works when it declares that.
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
//   ~detections/<camera>/image   bgr8, the detected marker points drawn, per sample as it is
//                       measured (latched), with ~detections/<camera>/camera_info beside it; the
//                       cameras are the sample net's `<camera>_image` outputs (left, right, or mono)
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
//   record_camera (the camera namespace the bag names; default the description's stereo
//   namespace, else "stereo"), server_timeout (s the start-up waits for the controllers the
//   description names; 10), calibration_camera (stereo or mono: the camera measured with; default
//   the description's head.calibration_camera), sample_net (the sample net run in place of ~net's
//   own, e.g. config/nets/calibration_sample_mono.yaml with calibration_camera mono; the node
//   refuses a sample net of other cameras). The robot's controllers and stereo namespace come from
//   its description (robot_interfaces.h: set on the nets at start-up; a named controller without a
//   server is an error in the log naming it); the acquisition's other settings (speed, timeouts,
//   settling) are properties of the sample net's blocks: use ~net for a net with other values.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <actionlib/server/simple_action_server.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include "imagenets/executor.h"
#include "imagenets/vision/marker.h"
#include "imagenets_calibration/bag_recorder.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/calibration_net_interface.h"
#include "imagenets_calibration/calibration_publisher.h"
#include "imagenets_calibration/calibration_run_watch.h"
#include "imagenets_calibration/storage.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets_calibration_msgs/CalibrateAction.h"

namespace imagenets_calibration {

class CalibrationNode {
 public:
  CalibrationNode(ros::NodeHandle nh, ros::NodeHandle pnh);

  // Feedback of one run (sample k of N, stage; the bounds reached after a pose added for a target).
  using Progress = CalibrationRunWatch::Progress;
  // One calibration (robot or replay). Never throws: failures come back with success = false.
  imagenets_calibration_msgs::Calibrate::Response run(const imagenets_calibration_msgs::Calibrate::Request& req, const Progress& progress);
  // Stops the running calibration (thread-safe; a no-op when none runs).
  void cancel();

 private:
  using Request = imagenets_calibration_msgs::Calibrate::Request;
  using Response = imagenets_calibration_msgs::Calibrate::Response;
  // How many poses a request takes: `requested` in any case, `total` at most (with a target).
  struct PoseCounts {
    int requested = 0, max_poses = 0, total = 0;
  };
  // What one run of the net gave.
  struct NetRun {
    Result result;
    CalibrationRunWatch::DetectionTime detection_time;
    CameraImages last_images;  // of the last sample
  };

  // ---- construction, in this order
  void readParameters();
  // Loads ~net (and its replay twin); a bad net is reported and every request answers with it.
  void loadNetsReporting();
  void setUpRecording(const std::string& joint_states);
  // Says at start-up which controllers the description names that no server offers.
  void checkControllers();
  // The last saved calibration (or a replayed file, or the nominal frame) published at start-up.
  void publishStartupCalibration();
  void startServices();

  bool onService(Request& req, Response& res);
  void onAction(const imagenets_calibration_msgs::CalibrateGoalConstPtr& goal);
  void onTf(const tf2_msgs::TFMessageConstPtr& msg, bool is_static);

  // Loads ~net (and its replay twin); throws naming the file, block or port that is wrong.
  void loadNets(const std::string& net, const std::string& replay_net);
  // The robot's description and ~target on every block of the nets that reads one.
  void setDescriptionAndTarget(const std::string& net);

  // ---- the steps of run()
  // "" and the node marked busy, or why the request is rejected (another calibration runs).
  std::string claim(const Request& req, int redundancy, const std::string& method);
  // Throws naming the request field that is out of range.
  static void checkRequest(const Request& req, const std::string& method);
  // The plan's and the solve's properties for this request.
  PoseCounts configureNet(const CalibrationNetInterface& net, const Request& req, int redundancy,
                          const std::string& method);
  // A recording of a live calibration (~record_bag), or null.
  std::shared_ptr<BagRecorder> startRecording(const Request& req);
  // Runs the net and returns its result; throws with the failure.
  NetRun runNet(const CalibrationNetInterface& net, const Progress& progress, const PoseCounts& poses);
  // One sample into the bag being recorded (none: nothing).
  void record(const CameraImages& images, const Sample& sample);
  // After a successful live run: saves the calibration, the URDF, the bag, the pictures, and
  // publishes it; fills the response.
  void saveAndPublish(const NetRun& run, const std::shared_ptr<BagRecorder>& recorder, const std::string& target_note,
                      Response& res);

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
  std::unique_ptr<CalibrationNetInterface> live_net_, replay_net_;
  std::string net_error_;  // why the nets did not load ("" when they did)
  std::atomic<imagenets::Executor*> running_{nullptr};

  std::unique_ptr<CalibrationPublisher> publisher_;
  ros::ServiceServer service_;
  std::unique_ptr<actionlib::SimpleActionServer<imagenets_calibration_msgs::CalibrateAction>> action_;
  std::mutex feedback_mutex_;

  // ~record_bag: the recording of the running calibration (null when none), the topics it names
  // and the static transforms so far (written at each recording's start: they are latched).
  std::string record_bag_, record_camera_topic_, record_joint_states_topic_;
  std::mutex recorder_mutex_;  // guards recorder_ and tf_static_
  std::shared_ptr<BagRecorder> recorder_;
  std::map<std::string, geometry_msgs::TransformStamped> tf_static_;
  ros::Subscriber tf_sub_, tf_static_sub_;

  std::mutex busy_mutex_;  // guards busy_with_, and busy_ being set
  std::atomic<bool> busy_{false};
  std::string busy_with_;
};

}  // namespace imagenets_calibration
