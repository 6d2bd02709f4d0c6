#include "friend_calibration/calibration_node.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>
#include <stdexcept>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <std_srvs/Trigger.h>
#include <geometry_msgs/TransformStamped.h>
#include <visualization_msgs/MarkerArray.h>

#include "imagenets/executor.h"
#include "imagenets/vision/frames.h"
#include "robot_description/joint_state.h"

namespace friend_calibration {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::string packageFile(const std::string& rel) {
  const std::string desc = robot_description::defaultRobotDescriptionPath();  // .../config/friend/robot.yaml
  return desc.substr(0, desc.size() - std::string("config/friend/robot.yaml").size()) + rel;
}

std::string defaultCalibrationFile() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string dir = ros_home ? ros_home : std::string(home ? home : "/tmp") + "/.ros";
  return dir + "/friend_calibration/pth_fixed_point.yaml";
}

template <class Out>
void fill(Out& out, const Result& r, const std::string& base, const std::string& child) {
  out.success = r.success;
  out.message = r.message;
  out.fixed_point = imagenets::frames::toTransformStamped(r.fixed_point, base, child, ros::Time::now());
  out.std_dev_translation = imagenets::frames::toVector3Msg(r.std_translation);
  out.std_dev_rotation = imagenets::frames::toVector3Msg(r.std_rotation);
  std::copy(r.fixed_point_covariance.data(), r.fixed_point_covariance.data() + 36, out.fixed_point_covariance.begin());
  out.samples_used = static_cast<int>(r.used.size());
  out.samples_rejected = static_cast<int>(r.rejected.size());
  out.rejected_samples = r.rejected;
  out.residual_translation = r.residual_translation;
  out.residual_rotation = r.residual_rotation;
  out.compute_time = r.compute_time;
}

// The detected marker points of one image drawn on it (bgr8): the outer corners as a red
// outline, the inner points green, and a line of text saying what was found. Used for the PNG
// files beside the calibration and for the live ~detections/... images.
cv::Mat drawObservation(const sensor_msgs::ImageConstPtr& img, const MarkerObservation& o, const char* side) {
  cv::Mat colour;
  cv::cvtColor(cv_bridge::toCvShare(img, "mono8")->image, colour, cv::COLOR_GRAY2BGR);
  // Line widths grow with the image so the overlay stays visible when shown scaled down (rviz).
  const int w = std::max(1, colour.cols / 400);
  for (size_t k = 0; k < o.points.size(); ++k) {
    const cv::Point2d p(o.points[k].x(), o.points[k].y());
    cv::circle(colour, p, 3 + 2 * w, k < 4 ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 200, 0), w, cv::LINE_AA);
    if (k < 4) cv::line(colour, p, cv::Point2d(o.points[(k + 1) % 4].x(), o.points[(k + 1) % 4].y()),
                        cv::Scalar(0, 0, 255), w, cv::LINE_AA);
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s: %s, confidence %.2f, threshold %.0f", side,
                o.found ? "marker found" : "marker NOT found", o.confidence, o.threshold);
  cv::putText(colour, text, cv::Point(10, 20 + 20 * w), cv::FONT_HERSHEY_SIMPLEX, 0.5 * w, cv::Scalar(0, 255, 255), w,
              cv::LINE_AA);
  return colour;
}

// The action's result and the service's response are one message definition (same fields, same
// MD5): converted through serialisation, so a field added to both needs no copying code.
template <class To, class From>
To sameMessage(const From& from) {
  if (std::string(ros::message_traits::md5sum<To>()) != ros::message_traits::md5sum<From>()) {
    throw std::logic_error(std::string(ros::message_traits::datatype<From>()) + " and " +
                           ros::message_traits::datatype<To>() + " differ: keep their fields identical");
  }
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(from));
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, from);
  To to;
  ros::serialization::IStream in(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, to);
  return to;
}

}  // namespace

CalibrationNode::CalibrationNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      model_(robot_description::loadRobotDescription(
          pnh.param<std::string>("description", robot_description::defaultRobotDescriptionPath()))),
      marker_(imagenets::marker::MarkerDescription::load(
          pnh.param<std::string>("marker", packageFile("config/markers/gripper.yaml")))) {
  // The robust detection is the net; the node's marker file is its detector's property.
  for (auto& net : detection_nets_) {
    net = std::make_unique<CalibrationMarkerNet>();
    net->executor().setPropertyText("detector", "marker",
                                    pnh_.param<std::string>("marker", packageFile("config/markers/gripper.yaml")));
  }
  calibration_file_ = pnh_.param<std::string>("calibration_file", defaultCalibrationFile());
  default_redundancy_ = pnh_.param("redundancy", 5);
  default_method_ = pnh_.param<std::string>("method", "joint");
  server_timeout_ = pnh_.param("server_timeout", 10.0);
  camera_timeout_ = pnh_.param("camera_timeout", 3.0);
  motion_timeout_ = pnh_.param("motion_timeout", 60.0);
  speed_scale_ = pnh_.param("speed_scale", 1.0);
  settle_time_ = pnh_.param("settle_time", 0.0);
  reapproach_ = pnh_.param("reapproach", true);
  poses_per_loop_ = pnh_.param("poses_per_loop", 2);
  min_valid_fraction_ = pnh_.param("min_valid_fraction", 0.5);
  fusion_.max_position_difference = pnh_.param("fusion/max_position_difference", fusion_.max_position_difference);
  fusion_.max_angle_difference = pnh_.param("fusion/max_angle_difference", fusion_.max_angle_difference);
  if (marker_.size != model_.description().marker_size) {
    ROS_WARN("marker file says %.3f m, robot description %.3f m: using the marker file's size", marker_.size,
             model_.description().marker_size);
  }

  arm_action_ = pnh_.param<std::string>("arm_action", "arm/move_joints");
  head_action_ = pnh_.param<std::string>("head_action", "head/move_joints");
  joint_sub_ = nh_.subscribe(pnh_.param<std::string>("joint_states", "joint_states"), 20,
                             &CalibrationNode::onJointStates, this);
  const std::string stereo = pnh_.param<std::string>("stereo_namespace", "stereo");
  for (int i = 0; i < 2; ++i) {
    const std::string side = i == 0 ? "/left" : "/right";
    image_sub_[i] = nh_.subscribe<sensor_msgs::Image>(stereo + side + "/image_raw", 4,
                                                      [this, i](const sensor_msgs::ImageConstPtr& m) { onImage(m, i == 0); });
    info_sub_[i] = nh_.subscribe<sensor_msgs::CameraInfo>(
        stereo + side + "/camera_info", 4, [this, i](const sensor_msgs::CameraInfoConstPtr& m) { onCameraInfo(m, i == 0); });
  }
  // Cameras that render on request (the simulator with camera/rate 0, or a triggered real camera).
  const std::string trigger = pnh_.param<std::string>("trigger_service", stereo + "/trigger");
  if (!trigger.empty()) trigger_ = nh_.serviceClient<std_srvs::Trigger>(trigger);
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  for (int i = 0; i < 2; ++i) {
    const std::string side = i == 0 ? "detections/left/" : "detections/right/";
    detection_image_pub_[i] = pnh_.advertise<sensor_msgs::Image>(side + "image", 1, true);
    detection_info_pub_[i] = pnh_.advertise<sensor_msgs::CameraInfo>(side + "camera_info", 1, true);
  }

  // The last saved calibration (or a replayed file) is published at start-up.
  const std::string replay = pnh_.param<std::string>("replay", "");
  const auto& base = model_.description().base_frame;
  try {
    if (!replay.empty()) {
      const StoredCalibration stored = loadCalibration(replay);
      const Result r = calibrate(model_, stored.result.samples, stored.result.method, fusion_, combine_);
      if (!r.success) throw std::runtime_error("replay of '" + replay + "' failed: " + r.message);
      ROS_INFO("replayed %s: %s", replay.c_str(), r.message.c_str());
      publish(r, child_frame_);
      publishSampleMarkers(r);
    } else if (std::ifstream(calibration_file_).good()) {
      const StoredCalibration stored = loadCalibration(calibration_file_);
      publish(stored.result, child_frame_);
      publishSampleMarkers(stored.result);
      ROS_INFO("loaded the calibration of %s from %s", stored.created.c_str(), calibration_file_.c_str());
    } else {
      ROS_WARN("no calibration yet (%s does not exist): publishing the nominal fixed point until calibrated",
               calibration_file_.c_str());
      Result nominal;
      nominal.fixed_point = model_.headBase();
      publish(nominal, child_frame_);
    }
  } catch (const std::exception& e) {
    ROS_ERROR("%s: publishing the nominal fixed point", e.what());
    Result nominal;
    nominal.fixed_point = model_.headBase();
    publish(nominal, child_frame_);
  }
  (void)base;

  service_ = pnh_.advertiseService("calibrate", &CalibrationNode::onService, this);
  action_ = std::make_unique<actionlib::SimpleActionServer<imagenets::CalibrateAction>>(
      pnh_, "calibrate_action", [this](const imagenets::CalibrateGoalConstPtr& g) { onAction(g); }, false);
  action_->start();
  ROS_INFO("friend_calibration: ready (%s, default redundancy %d, method %s, file %s)", model_.description().source.c_str(),
           default_redundancy_, default_method_.c_str(), calibration_file_.c_str());
}

void CalibrationNode::onJointStates(const sensor_msgs::JointStateConstPtr& msg) {
  {
    std::lock_guard<std::mutex> lock(data_mutex_);
    joints_ = msg;
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
  const Eigen::Isometry3d left = headChain(model_, head);
  const auto& d = model_.description();
  std::vector<geometry_msgs::TransformStamped> t{
      imagenets::frames::toTransformStamped(left, child_frame_, "calibrated/" + d.left_camera.frame, msg->header.stamp),
      imagenets::frames::toTransformStamped(left * model_.leftToRight(), child_frame_, "calibrated/" + d.right_camera_frame, msg->header.stamp)};
  tf_.sendTransform(t);
}

void CalibrationNode::onImage(const sensor_msgs::ImageConstPtr& msg, bool left) {
  std::lock_guard<std::mutex> lock(data_mutex_);
  auto& q = images_[left ? 0 : 1];
  q.push_back(msg);
  if (q.size() > 4) q.erase(q.begin());
}

void CalibrationNode::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg, bool left) {
  std::lock_guard<std::mutex> lock(data_mutex_);
  infos_[left ? 0 : 1] = msg;
}

bool CalibrationNode::onService(imagenets::Calibrate::Request& req, imagenets::Calibrate::Response& res) {
  res = run(req, Hooks{});
  return true;
}

void CalibrationNode::onAction(const imagenets::CalibrateGoalConstPtr& goal) {
  imagenets::Calibrate::Request req;
  req.redundancy = goal->redundancy;
  req.replay = goal->replay;
  req.method = goal->method;
  Hooks hooks;
  hooks.progress = [this](int k, int n, const std::string& stage) {
    imagenets::CalibrateFeedback f;
    f.sample = k;
    f.samples = n;
    f.stage = stage;
    action_->publishFeedback(f);
  };
  hooks.cancelled = [this] { return action_->isPreemptRequested() || !ros::ok(); };
  const auto res = run(req, hooks);
  const auto result = sameMessage<imagenets::CalibrateResult>(res);
  if (res.success) {
    action_->setSucceeded(result);
  } else if (action_->isPreemptRequested()) {
    action_->setPreempted(result, res.message);
  } else {
    action_->setAborted(result, res.message);
  }
}

imagenets::Calibrate::Response CalibrationNode::run(const imagenets::Calibrate::Request& req, const Hooks& hooks) {
  imagenets::Calibrate::Response res;
  const auto& base = model_.description().base_frame;
  const int n = req.redundancy > 0 ? req.redundancy : default_redundancy_;
  const std::string method = req.method.empty() ? default_method_ : req.method;
  {
    // One lock for the flag and its description: triggers arrive on several spinner threads at once.
    std::lock_guard<std::mutex> lock(busy_mutex_);
    if (busy_) {
      res.success = false;
      res.message = "rejected: a calibration is already running (" + busy_with_ + "); try again when it has finished";
      return res;
    }
    busy_ = true;
    busy_with_ = (req.replay.empty() ? "redundancy " + std::to_string(n) : "replay of " + req.replay) + ", method " +
                 method + ", started " + utcStamp(true);
  }
  struct Release {
    std::atomic<bool>& b;
    ~Release() { b = false; }
  } release{busy_};
  const auto start = std::chrono::steady_clock::now();
  try {
    if (method != "paper" && method != "joint") {
      throw std::runtime_error("unknown method '" + method + "' (expected 'paper' or 'joint')");
    }
    if (!req.replay.empty()) {
      // Re-solve stored samples: no robot, nothing saved or published.
      const StoredCalibration stored = loadCalibration(req.replay);
      const Result r = calibrate(model_, stored.result.samples, method, fusion_, combine_);
      fill(res, r, base, child_frame_);
      res.message = "replay of " + std::to_string(r.samples.size()) + " stored samples from " + req.replay + ": " +
                    r.message;
      res.total_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return res;
    }
    if (n < 1 || n % 2 == 0) {
      throw std::runtime_error("redundancy must be odd and >= 1 (the per-axis median needs a middle value), got " +
                               std::to_string(n));
    }
    // The joint method visits `poses_per_loop` different poses per loop (its unknowns need varied
    // poses); the paper's method one pose per loop.
    const int total = method == "joint" ? n * std::max(1, poses_per_loop_) : n;
    detection_time_ = 0;
    std::vector<Sample> samples = collectSamples(total, method, hooks);
    if (hooks.progress) hooks.progress(total, total, "solving");
    CombineOptions combine = combine_;
    combine.min_valid_samples = std::max(1, static_cast<int>(std::ceil(min_valid_fraction_ * total)));
    const Result r = calibrate(model_, std::move(samples), method, fusion_, combine);
    fill(res, r, base, child_frame_);
    res.compute_time = r.compute_time + detection_time_;  // image processing + solving, no motion
    res.total_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!r.success) {
      res.message = "calibration failed: " + r.message + "; the saved calibration and the published frame are unchanged";
      return res;
    }
    StoredCalibration stored;
    stored.base_frame = base;
    stored.child_frame = child_frame_;
    stored.result = r;
    const std::string archived = saveCalibration(stored, calibration_file_);
    res.file = calibration_file_;
    const std::string pictures = savePictures(r.samples.back());
    publish(r, child_frame_);
    publishSampleMarkers(r);
    const Eigen::Vector3d t = r.fixed_point.translation();
    char b[256];
    std::snprintf(b, sizeof b, "; fixed point [%.4f %.4f %.4f] m; saved to %s", t.x(), t.y(), t.z(),
                  calibration_file_.c_str());
    res.message = r.message + b + (archived.empty() ? "" : " (previous kept as " + archived + ")") +
                  (pictures.empty() ? "" : "; pictures: " + pictures);
    ROS_INFO("%s", res.message.c_str());
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("calibration failed: ") + e.what() +
                  "; the saved calibration and the published frame are unchanged";
    res.total_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ROS_WARN("%s", res.message.c_str());
  }
  return res;
}

void CalibrationNode::moveBoth(Motion& motion, const CalibrationPose& pose, int sample, const Hooks& hooks) {
  imagenets::MoveJointsGoal arm_goal, head_goal;
  arm_goal.positions = pose.arm;
  arm_goal.speed_scale = speed_scale_;
  head_goal.positions = pose.head;
  head_goal.speed_scale = speed_scale_;
  MoveClient& arm = motion.arm;
  MoveClient& head = motion.head;
  arm.sendGoal(arm_goal);
  head.sendGoal(head_goal);
  bool cancelled = false;
  MoveClient* lost = nullptr;  // a server that went away mid-motion (the robot's driver stopped)
  const bool finished = motion.queue.waitUntil(
      [&] {
        cancelled = hooks.cancelled && hooks.cancelled();
        for (auto* c : {&arm, &head}) {
          if (!c->getState().isDone() && !c->isServerConnected()) lost = c;
        }
        return cancelled || lost || (arm.getState().isDone() && head.getState().isDone());
      },
      motion_timeout_);
  if (cancelled || lost || !finished) {
    arm.cancelGoal();
    head.cancelGoal();
    if (cancelled) throw std::runtime_error("cancelled during the motion of sample " + std::to_string(sample + 1));
    if (lost) {
      throw std::runtime_error(std::string(lost == &arm ? "arm" : "head") + " action server lost during the motion of sample " +
                               std::to_string(sample + 1) + " (the robot's driver / friend_sim stopped?)");
    }
    throw std::runtime_error("motion of sample " + std::to_string(sample + 1) + " did not finish within " +
                             std::to_string(motion_timeout_) + " s");
  }
  for (auto* c : {&arm, &head}) {
    const auto state = c->getState();
    if (state != actionlib::SimpleClientGoalState::SUCCEEDED) {
      const auto result = c->getResult();
      const std::string which = c == &arm ? "arm" : "head";
      throw std::runtime_error(which + " goal " + state.toString() + " at sample " + std::to_string(sample + 1) + ": " +
                               (result && !result->message.empty() ? result->message : state.getText()));
    }
  }
}

CalibrationNode::StereoPair CalibrationNode::waitForStereoPair(const ros::Time& after, const Hooks& hooks) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(camera_timeout_);
  while (ros::ok()) {
    {
      std::lock_guard<std::mutex> lock(data_mutex_);
      // The newest left image taken after the motion with a right image of the same stamp.
      for (auto l = images_[0].rbegin(); l != images_[0].rend(); ++l) {
        if ((*l)->header.stamp <= after) break;
        for (const auto& r : images_[1]) {
          if (r->header.stamp == (*l)->header.stamp && infos_[0] && infos_[1]) {
            return StereoPair{*l, r, infos_[0], infos_[1]};
          }
        }
      }
    }
    if (hooks.cancelled && hooks.cancelled()) throw std::runtime_error("cancelled while waiting for images");
    if (ros::WallTime::now() > deadline) break;
    ros::WallDuration(0.005).sleep();
  }
  std::lock_guard<std::mutex> lock(data_mutex_);
  std::ostringstream why;
  why << "camera silent: no stereo image pair (" << image_sub_[0].getTopic() << " + " << image_sub_[1].getTopic()
      << " with equal stamps, and camera_info) within " << camera_timeout_ << " s after the motion (images received: "
      << images_[0].size() << " left, " << images_[1].size() << " right)";
  throw std::runtime_error(why.str());
}

sensor_msgs::JointStateConstPtr CalibrationNode::waitForJointStates(const ros::Time& after) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(camera_timeout_);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(data_mutex_);
      if (joints_ && joints_->header.stamp >= after) return joints_;
    }
    ros::WallDuration(0.002).sleep();
  }
  throw std::runtime_error("no joint_states on " + joint_sub_.getTopic() + " within " + std::to_string(camera_timeout_) +
                           " s");
}

Sample CalibrationNode::measure(const StereoPair& pair, const sensor_msgs::JointState& joints) {
  const auto& d = model_.description();
  Sample s;
  s.arm_q = robot_description::jointPositions(joints, d.arm.names());
  s.head_q = robot_description::jointPositions(joints, d.head.names());
  s.stamp = pair.left->header.stamp.toSec();
  // Where the nominal model expects the marker: region of interest and pose-ambiguity hint.
  const Eigen::Isometry3d marker = model_.marker(s.arm_q);
  const Eigen::Isometry3d predicted_left = model_.leftCamera(s.head_q).inverse() * marker;
  const Eigen::Isometry3d predicted_right = model_.rightCamera(s.head_q).inverse() * marker;
  auto detect = [this](int side, const sensor_msgs::ImageConstPtr& img, const sensor_msgs::CameraInfoConstPtr& info,
                       const Eigen::Isometry3d& predicted) {
    MarkerObservation o;
    try {
      o = detection_nets_[side]->detect(img, *info, predicted);
    } catch (const std::exception& e) {
      o.found = false;
      o.reason = std::string(side == 0 ? "left" : "right") + " image unusable: " + e.what();
    }
    return o;
  };
  // Left and right in parallel (the two Fig. 3.3 sub-nets of Fig. 4.2), each on its own net.
  auto right = std::async(std::launch::async, detect, 1, pair.right, pair.right_info, predicted_right);
  s.left = detect(0, pair.left, pair.left_info, predicted_left);
  s.right = right.get();
  return s;
}

std::vector<Sample> CalibrationNode::collectSamples(int n, const std::string& method, const Hooks& hooks) {
  Motion motion(nh_, arm_action_, head_action_);
  for (auto* c : {&motion.arm, &motion.head}) {
    if (!motion.queue.waitUntil([c] { return c->isServerConnected(); }, server_timeout_)) {
      std::ostringstream why;
      why << (c == &motion.arm ? "arm" : "head") << " action server is not available after " << server_timeout_
          << " s (is the robot / friend_sim running?)";
      throw std::runtime_error(why.str());
    }
  }
  const auto poses = calibrationPoses(model_, n, method);
  std::vector<Sample> samples;
  for (int k = 0; k < n; ++k) {
    if (hooks.progress) hooks.progress(k + 1, n, "moving");
    if (reapproach_ && method == "paper") {
      // Every loop of the paper's procedure comes to the calibration pose anew (the first one
      // too: the same approach whatever pose the robot starts from).
      CalibrationPose away = poses[k];
      away.arm[3] -= 10 * kDeg;
      moveBoth(motion, away, k, hooks);
    }
    moveBoth(motion, poses[k], k, hooks);
    if (settle_time_ > 0) ros::WallDuration(settle_time_).sleep();
    const ros::Time after = ros::Time::now();
    if (hooks.progress) hooks.progress(k + 1, n, "acquiring");
    if (trigger_ && trigger_.exists()) {
      std_srvs::Trigger t;
      trigger_.call(t);  // a failed trigger shows as a silent camera below
    }
    const StereoPair pair = waitForStereoPair(after, hooks);
    const auto joints = waitForJointStates(after);
    if (hooks.progress) hooks.progress(k + 1, n, "detecting");
    const auto t0 = std::chrono::steady_clock::now();
    samples.push_back(measure(pair, *joints));
    detection_time_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    publishDetections(pair, samples.back());
    {
      std::lock_guard<std::mutex> lock(data_mutex_);
      last_pair_ = {pair.left, pair.right, pair.left_info, pair.right_info};
    }
    ROS_INFO("sample %d/%d: left %s (conf %.2f), right %s (conf %.2f)", k + 1, n, samples.back().left.found ? "found" : "not found",
             samples.back().left.confidence, samples.back().right.found ? "found" : "not found",
             samples.back().right.confidence);
  }
  return samples;
}

std::string CalibrationNode::savePictures(const Sample& sample) {
  // The last stereo pair with the detected marker points drawn, beside the calibration file.
  StereoPair pair;
  {
    std::lock_guard<std::mutex> lock(data_mutex_);
    pair = last_pair_;
  }
  if (!pair.left || !pair.right) return "";
  const std::string stem = calibration_file_.substr(0, calibration_file_.rfind('.'));
  std::string written;
  try {
    for (int i = 0; i < 2; ++i) {
      const auto& img = i == 0 ? pair.left : pair.right;
      const cv::Mat colour = drawObservation(img, i == 0 ? sample.left : sample.right, i == 0 ? "left" : "right");
      const std::string path = stem + (i == 0 ? "_left.png" : "_right.png");
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

void CalibrationNode::publishDetections(const StereoPair& pair, const Sample& sample) {
  // Always drawn (a few ms), so a late subscriber of the latched topic gets the newest sample.
  for (int i = 0; i < 2; ++i) {
    const auto& img = i == 0 ? pair.left : pair.right;
    try {
      const cv::Mat colour = drawObservation(img, i == 0 ? sample.left : sample.right, i == 0 ? "left" : "right");
      detection_image_pub_[i].publish(cv_bridge::CvImage(img->header, "bgr8", colour).toImageMsg());
      detection_info_pub_[i].publish(i == 0 ? pair.left_info : pair.right_info);
    } catch (const std::exception& e) {
      ROS_WARN("detection image of the %s camera not published: %s", i == 0 ? "left" : "right", e.what());
    }
  }
}

void CalibrationNode::publish(const Result& result, const std::string& frame) {
  const auto& base = model_.description().base_frame;
  const ros::Time now = ros::Time::now();
  std::vector<geometry_msgs::TransformStamped> t{imagenets::frames::toTransformStamped(result.fixed_point, base, frame, now),
                                                 imagenets::frames::toTransformStamped(model_.headBase(), base, frame + "_nominal", now)};
  static_tf_.sendTransform(t);
  std::lock_guard<std::mutex> lock(calibration_mutex_);
  current_ = result.fixed_point;
  have_calibration_ = true;
}

void CalibrationNode::publishSampleMarkers(const Result& result) {
  // The marker pose of every sample as the calibrated chain sees it (fixed point * head chain *
  // detection): a tight cluster around the gripper marker means a consistent calibration.
  visualization_msgs::MarkerArray array;
  visualization_msgs::Marker clear;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);
  const auto& base = model_.description().base_frame;
  for (size_t i = 0; i < result.samples.size(); ++i) {
    Sample s = result.samples[i];
    if (s.head_q.size() != 2 || s.arm_q.size() != model_.description().arm.joints.size()) continue;
    solveSample(model_, s, fusion_, result.marker_offset);
    if (!s.valid) continue;
    const Eigen::Isometry3d pose = result.fixed_point * headChain(model_, s.head_q) * s.marker_in_left;
    visualization_msgs::Marker m;
    m.header.frame_id = base;
    m.header.stamp = ros::Time::now();
    m.ns = "calibration_samples";
    m.id = static_cast<int>(i);
    m.type = visualization_msgs::Marker::CUBE;
    m.pose = imagenets::frames::toPose(pose);
    m.scale.x = m.scale.y = marker_.size;
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

}  // namespace friend_calibration
