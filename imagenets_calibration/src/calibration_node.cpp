#include "imagenets_calibration/calibration_node.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <geometry_msgs/TransformStamped.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <imagenets_calibration_msgs/CalibrationSample.h>
#include <visualization_msgs/MarkerArray.h>

#include "imagenets_calibration/bag_samples.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/vision/frames.h"
#include "imagenets/inner_net.h"
#include "imagenets/net_wide_property.h"
#include "imagenets/package_file.h"
#include "robot_description/joint_state.h"
#include "imagenets/vision/target.h"

namespace imagenets_calibration {
namespace {

// A required private parameter; throws naming it when it is missing or empty.
std::string requiredParam(const ros::NodeHandle& pnh, const std::string& name, const std::string& what) {
  std::string value;
  if (!pnh.getParam(name, value) || value.empty()) {
    throw std::runtime_error("parameter " + pnh.resolveName(name) + " (" + what + ") is not set");
  }
  return value;
}

std::string defaultCalibrationFile() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string dir = ros_home ? ros_home : std::string(home ? home : "/tmp") + "/.ros";
  return dir + ros::this_node::getName() + "/pth_fixed_point.yaml";
}

// The fixed point's 3-sigma bounds (0 without a covariance) into a response, result or feedback.
template <class Out>
void fillBounds(Out& out, const Result& r) {
  out.uncertainty = r.has_covariance ? 3 * r.sigmaTranslation() : 0.0;
  out.uncertainty_rotation = r.has_covariance ? 3 * r.sigmaRotation() : 0.0;
}

template <class Out>
void fill(Out& out, const Result& r, const std::string& base, const std::string& child) {
  summarize(toMsg(r, base, child), out);
  out.fixed_point.header.stamp = ros::Time::now();
  fillBounds(out, r);
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
    // The outline of the square marker or of one tag; a grid's or board's corners as dots.
    const bool outline = o.points.size() == 8 || o.points.size() == 4;
    if (k < 4 && outline) cv::line(colour, p, cv::Point2d(o.points[(k + 1) % 4].x(), o.points[(k + 1) % 4].y()),
                        cv::Scalar(0, 0, 255), w, cv::LINE_AA);
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s: %s, confidence %.2f, threshold %.0f", side,
                o.found ? "marker found" : "marker NOT found", o.confidence, o.threshold);
  cv::putText(colour, text, cv::Point(10, 20 + 20 * w), cv::FONT_HERSHEY_SIMPLEX, 0.5 * w, cv::Scalar(0, 255, 255), w,
              cv::LINE_AA);
  return colour;
}

// "; uncertainty target met: 3 sigma 0.312 mm / 0.0310 deg after 12 poses (target 0.400 mm, at
// most 30 poses)" -- or "NOT met".
std::string targetNote(const imagenets_calibration_msgs::Calibrate::Response& res, double target, double target_rotation, int max_poses) {
  std::string bounds = "no uncertainty";
  std::string wanted;
  char b[160];
  if (res.uncertainty > 0) {
    std::snprintf(b, sizeof b, "3 sigma %.3f mm / %.4f deg", 1000 * res.uncertainty, res.uncertainty_rotation * 180 / M_PI);
    bounds = b;
  }
  if (target > 0) {
    std::snprintf(b, sizeof b, "%.3f mm", 1000 * target);
    wanted = b;
  }
  if (target_rotation > 0) {
    std::snprintf(b, sizeof b, "%s%.4f deg", wanted.empty() ? "" : " / ", target_rotation * 180 / M_PI);
    wanted += b;
  }
  return std::string("; uncertainty target ") + (res.target_met ? "met: " : "NOT met: ") + bounds + " after " +
         std::to_string(res.poses_taken) + " poses (target " + wanted + ", at most " + std::to_string(max_poses) +
         " poses)";
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
          requiredParam(pnh, "description", "the robot's description YAML"))),
      marker_(imagenets::marker::MarkerDescription::load(
          requiredParam(pnh, "marker", "the marker's description YAML"))) {
  calibration_file_ = pnh_.param<std::string>("calibration_file", defaultCalibrationFile());
  urdf_file_ = pnh_.param<std::string>("urdf_file", urdfFileBeside(calibration_file_));
  default_redundancy_ = pnh_.param("redundancy", 5);
  default_method_ = pnh_.param<std::string>("method", "joint");
  poses_per_loop_ = pnh_.param("poses_per_loop", 2);
  max_poses_ = pnh_.param("max_poses", 30);
  min_valid_fraction_ = pnh_.param("min_valid_fraction", 0.5);
  fusion_.max_position_difference = pnh_.param("fusion/max_position_difference", fusion_.max_position_difference);
  fusion_.max_angle_difference = pnh_.param("fusion/max_angle_difference", fusion_.max_angle_difference);
  if (marker_.size != model_.description().marker_size) {
    ROS_WARN("marker file says %.3f m, robot description %.3f m: using the marker file's size", marker_.size,
             model_.description().marker_size);
  }
  // The nets, once. A bad net is reported (and every request answers with it); the node keeps
  // serving the previous calibration.
  net_file_ = requiredParam(pnh_, "net", "the calibration net");
  try {
    loadNets(net_file_, pnh_.param<std::string>("replay_net", imagenets::packageFile("imagenets_calibration", "config/nets/calibration_sample_replay.yaml")));
  } catch (const std::exception& e) {
    net_error_ = e.what();
    ROS_ERROR("%s: the calibration net is not usable: %s", ros::this_node::getName().c_str(), net_error_.c_str());
  }

  const std::string joint_states = pnh_.param<std::string>("joint_states", "joint_states");
  joint_sub_ = nh_.subscribe(joint_states, 20, &CalibrationNode::onJointStates, this);
  record_bag_ = pnh_.param<std::string>("record_bag", "");
  if (!record_bag_.empty()) {
    record_bag_ = boost::filesystem::absolute(record_bag_).string();
    BagSampleSettings topics;
    topics.camera = nh_.resolveName(pnh_.param<std::string>("record_camera", "stereo"));
    record_camera_topic_ = topics.camera;
    record_joint_states_topic_ = nh_.resolveName(joint_states);
    tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf", 100, [this](const tf2_msgs::TFMessageConstPtr& m) { onTf(m, false); });
    tf_static_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf_static", 100,
                                                        [this](const tf2_msgs::TFMessageConstPtr& m) { onTf(m, true); });
  }
  markers_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  for (int i = 0; i < 2; ++i) {
    const std::string side = i == 0 ? "detections/left/" : "detections/right/";
    detection_image_pub_[i] = pnh_.advertise<sensor_msgs::Image>(side + "image", 1, true);
    detection_info_pub_[i] = pnh_.advertise<sensor_msgs::CameraInfo>(side + "camera_info", 1, true);
  }

  // The last saved calibration (or a replayed file) is published at start-up.
  const std::string replay = pnh_.param<std::string>("replay", "");
  try {
    if (!replay.empty()) {
      imagenets_calibration_msgs::Calibrate::Request req;
      req.replay = replay;
      req.method = default_method_;
      const auto res = run(req, {});
      if (!res.success) throw std::runtime_error(res.message);
      ROS_INFO("%s", res.message.c_str());
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

  service_ = pnh_.advertiseService("calibrate", &CalibrationNode::onService, this);
  action_ = std::make_unique<actionlib::SimpleActionServer<imagenets_calibration_msgs::CalibrateAction>>(
      pnh_, "calibrate_action", [this](const imagenets_calibration_msgs::CalibrateGoalConstPtr& g) { onAction(g); }, false);
  action_->registerPreemptCallback([this] { cancel(); });
  action_->start();
  ROS_INFO("%s: ready (%s, net %s, default redundancy %d, method %s, file %s)",
           ros::this_node::getName().c_str(), model_.description().source.c_str(), net_file_.c_str(), default_redundancy_, default_method_.c_str(),
           calibration_file_.c_str());
}

void CalibrationNode::loadNets(const std::string& net, const std::string& replay_net) {
  const imagenets::NetSpec spec = imagenets::parseNetFile(net);
  // What the node sets and reads: named, so a net of one's own says at once what it lacks.
  auto need = [&](const std::string& block, const std::string& what) {
    if (std::none_of(spec.blocks.begin(), spec.blocks.end(), [&](const auto& b) { return b.name == block; })) {
      throw std::runtime_error(net + ": no block '" + block + "' (" + what + ")");
    }
  };
  need("plan", "an imagenets_calibration_msgs/CalibrationPlan: the node sets its method, loops, replay");
  need("samples", "the imagenets/SubNet running the sample net: a replay runs it with " + replay_net);
  need("solve", "an imagenets/SolveCalibration: the node sets its limits");
  imagenets::NetSpec replay_spec = spec;
  for (auto& b : replay_spec.blocks) {
    if (b.name != "samples") continue;
    for (auto& p : b.properties) {
      if (p.name == "net") p.text = replay_net;
    }
  }
  auto build = [&](const imagenets::NetSpec& s) {
    auto exec = std::make_unique<imagenets::Executor>(imagenets::Net::build(s));
    const imagenets::Endpoint result = exec->net().resolveOutput("result.value");  // throws naming the port
    const auto& type = exec->net().node(result.node).block->outputs()[result.port].type->name;
    if (type != "imagenets_calibration_msgs/CalibrationResult") {
      throw std::runtime_error(s.origin + ": output 'result' is " + type + ", expected imagenets_calibration_msgs/CalibrationResult");
    }
    return exec;
  };
  live_ = build(spec);
  replay_ = build(replay_spec);
  // The robot this node calibrates, for every block of its nets (sub-nets included) that reads a
  // robot description from a path property `description`: their own default is FRIEND's.
  const std::string description = boost::filesystem::absolute(model_.description().source).string();
  for (imagenets::Executor* exec : {live_.get(), replay_.get()}) {
    const auto set = imagenets::setPropertyInNetTree(*exec, "description", description,
                                                     [](const imagenets::PropertySpec& p) { return p.isPath(); });
    ROS_DEBUG("%s: description %s set on %zu blocks", exec->net().origin().c_str(), description.c_str(), set.size());
  }
  // What the gripper carries, when not the nets' own square marker: a target file (~target,
  // config/targets/ of imagenets_vision) for every block that reads one; the sample net's detection
  // (imagenets/TargetDetectionNet) runs the detection net of its kind with it.
  const std::string target = pnh_.param<std::string>("target", "");
  if (!target.empty()) {
    const auto t = imagenets::target::TargetDescription::load(target);  // a bad file: named here
    const std::string path = boost::filesystem::absolute(target).string();
    size_t blocks = 0;
    for (imagenets::Executor* exec : {live_.get(), replay_.get()}) {
      blocks += imagenets::setPropertyInNetTree(*exec, "target", path,
                                                [](const imagenets::PropertySpec& p) { return p.isPath(); })
                    .size();
    }
    if (blocks == 0) throw std::runtime_error(net + ": no block of it or its sub-nets takes a target file (~target " + path + ")");
    ROS_INFO("%s: target %s (%s) set on %zu blocks", net.c_str(), path.c_str(), t.typeName().c_str(), blocks);
  }
}

imagenets::Executor* CalibrationNode::untilNet(const imagenets::Executor& exec) {
  const int samples = exec.net().findNode("samples");
  auto* inner = samples < 0 ? nullptr : dynamic_cast<imagenets::InnerNet*>(exec.net().node(samples).block.get());
  if (!inner) return nullptr;
  for (const imagenets::InnerExecutorRef& net : inner->innerExecutors()) {
    if (net.path == "until") return net.executor;
  }
  return nullptr;
}

void CalibrationNode::onJointStates(const sensor_msgs::JointStateConstPtr& msg) {
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
  const Eigen::Isometry3d left = headChain(model, head);
  const auto& d = model_.description();
  std::vector<geometry_msgs::TransformStamped> t{
      imagenets::frames::toTransformStamped(left, child_frame_, "calibrated/" + d.left_camera.frame, msg->header.stamp),
      imagenets::frames::toTransformStamped(left * model.leftToRight(), child_frame_, "calibrated/" + d.right_camera_frame, msg->header.stamp)};
  tf_.sendTransform(t);
}

void CalibrationNode::onTf(const tf2_msgs::TFMessageConstPtr& msg, bool is_static) {
  std::lock_guard<std::mutex> lock(recorder_mutex_);
  if (is_static) {
    for (const auto& t : msg->transforms) tf_static_[t.child_frame_id] = t;
  }
  if (recorder_) recorder_->write(is_static ? "/tf_static" : "/tf", ros::Time::now(), *msg);
}

void CalibrationNode::record(const StereoPair& pair, const Sample& sample) {
  std::shared_ptr<BagRecorder> recorder;
  {
    std::lock_guard<std::mutex> lock(recorder_mutex_);
    recorder = recorder_;
  }
  if (!recorder) return;
  // The bag's topics as the camera and joint_states publish them; the joint readings are the ones
  // the sample used, stamped with its image, so the bag's sample is exactly this one.
  BagSampleSettings topics;
  topics.camera = record_camera_topic_;
  topics.joint_states = record_joint_states_topic_;
  const ros::Time t = pair.left->header.stamp.isZero() ? ros::Time::now() : pair.left->header.stamp;
  recorder->write(topics.imageTopic("left"), t, *pair.left);
  recorder->write(topics.imageTopic("right"), t, *pair.right);
  recorder->write(topics.infoTopic("left"), t, *pair.left_info);
  recorder->write(topics.infoTopic("right"), t, *pair.right_info);
  sensor_msgs::JointState joints;
  joints.header.stamp = pair.left->header.stamp;
  joints.name = sampleJoints(model_);
  joints.position = sample.arm_q;
  joints.position.insert(joints.position.end(), sample.head_q.begin(), sample.head_q.end());
  recorder->write(topics.jointStatesTopic(), t, joints);
}

bool CalibrationNode::onService(imagenets_calibration_msgs::Calibrate::Request& req, imagenets_calibration_msgs::Calibrate::Response& res) {
  res = run(req, {});
  return true;
}

void CalibrationNode::cancel() {
  if (imagenets::Executor* exec = running_.load()) exec->cancel();
}

void CalibrationNode::onAction(const imagenets_calibration_msgs::CalibrateGoalConstPtr& goal) {
  imagenets_calibration_msgs::Calibrate::Request req;
  req.redundancy = goal->redundancy;
  req.replay = goal->replay;
  req.method = goal->method;
  req.poses = goal->poses;
  req.target_uncertainty = goal->target_uncertainty;
  req.target_uncertainty_rotation = goal->target_uncertainty_rotation;
  req.max_poses = goal->max_poses;
  auto progress = [this](const imagenets_calibration_msgs::CalibrateFeedback& f) {
    std::lock_guard<std::mutex> lock(feedback_mutex_);
    action_->publishFeedback(f);
  };
  imagenets_calibration_msgs::Calibrate::Response res;
  res.message = "cancelled before it started";
  if (!action_->isPreemptRequested()) res = run(req, progress);
  const auto result = sameMessage<imagenets_calibration_msgs::CalibrateResult>(res);
  if (res.success) {
    action_->setSucceeded(result);
  } else if (action_->isPreemptRequested()) {
    action_->setPreempted(result, res.message);
  } else {
    action_->setAborted(result, res.message);
  }
}

imagenets_calibration_msgs::Calibrate::Response CalibrationNode::run(const imagenets_calibration_msgs::Calibrate::Request& req, const Progress& progress) {
  imagenets_calibration_msgs::Calibrate::Response res;
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
    busy_with_ = (req.replay.empty() ? req.poses > 0 ? std::to_string(req.poses) + " poses" : "redundancy " + std::to_string(n)
                                     : "replay of " + req.replay) +
                 (req.target_uncertainty > 0 || req.target_uncertainty_rotation > 0 ? " until certain" : "") +
                 ", method " + method + ", started " + utcStamp(true);
  }
  struct Release {
    std::atomic<bool>& b;
    ~Release() { b = false; }
  } release{busy_};
  const auto start = std::chrono::steady_clock::now();
  try {
    if (!net_error_.empty()) throw std::runtime_error("the calibration net is not usable: " + net_error_);
    if (method != "paper" && method != "joint") {
      throw std::runtime_error("unknown method '" + method + "' (expected 'paper' or 'joint')");
    }
    if (req.poses < 0) throw std::runtime_error("request field 'poses' is " + std::to_string(req.poses) + " (expected >= 0)");
    // The uncertainty target (joint method): after the requested poses, the plan's next ones until
    // the fixed point's 3-sigma bounds are within it; the loop is the net's (calibration_target.yaml).
    if (!(req.target_uncertainty >= 0) || !std::isfinite(req.target_uncertainty)) {
      throw std::runtime_error("request field 'target_uncertainty' is " + std::to_string(req.target_uncertainty) +
                               " (expected >= 0: the fixed point's 3-sigma translation bound to reach, m; 0 = off)");
    }
    if (!(req.target_uncertainty_rotation >= 0) || !std::isfinite(req.target_uncertainty_rotation)) {
      throw std::runtime_error("request field 'target_uncertainty_rotation' is " +
                               std::to_string(req.target_uncertainty_rotation) +
                               " (expected >= 0: the fixed point's 3-sigma rotation bound to reach, rad; 0 = off)");
    }
    if (req.max_poses < 0) {
      throw std::runtime_error("request field 'max_poses' is " + std::to_string(req.max_poses) + " (expected >= 0)");
    }
    const bool target = req.target_uncertainty > 0 || req.target_uncertainty_rotation > 0;
    if (target && !req.replay.empty()) {
      throw std::runtime_error("request field 'target_uncertainty': a replay re-solves the stored samples and "
                               "cannot take more poses (leave the target 0 for a replay)");
    }
    // The plan and the solve's limits are the net's properties.
    imagenets::Executor& exec = req.replay.empty() ? *live_ : *replay_;
    exec.setProperty("plan", "method", method);
    exec.setProperty("plan", "replay", req.replay.empty() ? std::string() : boost::filesystem::absolute(req.replay).string());
    exec.setProperty("plan", "loops", n);
    exec.setProperty("plan", "poses_per_loop", poses_per_loop_);
    exec.setProperty("plan", "poses", static_cast<int>(req.poses));
    const int requested = !req.replay.empty() ? 0
                          : req.poses > 0     ? static_cast<int>(req.poses)
                                              : n * (method == "joint" ? std::max(1, poses_per_loop_) : 1);
    const int max_poses = req.max_poses > 0 ? static_cast<int>(req.max_poses) : std::max(max_poses_, requested);
    exec.setProperty("plan", "target_uncertainty", static_cast<double>(req.target_uncertainty));
    exec.setProperty("plan", "target_uncertainty_rotation", static_cast<double>(req.target_uncertainty_rotation));
    exec.setProperty("plan", "max_poses", std::max(1, max_poses));
    // The solve's limits, for the net's solve and for the one that decides whether a target is met.
    imagenets::Executor* until = untilNet(exec);
    for (imagenets::Executor* e : {&exec, until}) {
      if (!e || e->net().findNode("solve") < 0) continue;
      e->setProperty("solve", "max_position_difference", fusion_.max_position_difference);
      e->setProperty("solve", "max_angle_difference", fusion_.max_angle_difference);
      e->setProperty("solve", "min_valid_fraction", min_valid_fraction_);
    }
    const int total = target ? max_poses : requested;
    StereoPair last_pair;
    DetectionTime detection_time;
    // What a live calibration saw, into a bag put in place only when the calibration succeeds.
    std::shared_ptr<BagRecorder> recorder;
    if (!record_bag_.empty() && req.replay.empty()) {
      recorder = std::make_shared<BagRecorder>(record_bag_);
      std::lock_guard<std::mutex> lock(recorder_mutex_);
      tf2_msgs::TFMessage statics;
      for (const auto& t : tf_static_) statics.transforms.push_back(t.second);
      if (!statics.transforms.empty()) recorder->write("/tf_static", ros::Time::now(), statics);
      recorder_ = recorder;
    }
    struct StopRecording {
      std::mutex& m;
      std::shared_ptr<BagRecorder>& r;
      ~StopRecording() {
        std::lock_guard<std::mutex> lock(m);
        r.reset();
      }
    } stop_recording{recorder_mutex_, recorder_};
    const Result r = runNet(exec, progress, total, requested, &last_pair, &detection_time);
    fill(res, r, base, child_frame_);
    res.target_met = r.withinUncertaintyTarget(req.target_uncertainty, req.target_uncertainty_rotation);
    const std::string target_note =
        target ? targetNote(res, req.target_uncertainty, req.target_uncertainty_rotation, max_poses) : "";
    res.total_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!req.replay.empty()) {
      // Re-solved stored samples: no robot, nothing saved or published.
      res.message = "replay of " + std::to_string(r.samples.size()) + " stored samples from " + req.replay + ": " +
                    r.message;
      if (!r.success) res.message = "calibration failed: " + res.message;
      return res;
    }
    res.compute_time = r.compute_time + detection_time.wall;  // image processing + solving, no motion
    res.detection_cpu_time = detection_time.cpu;
    if (!r.success) {
      res.message = "calibration failed: " + r.message + target_note +
                    "; the saved calibration and the published frame are unchanged";
      return res;
    }
    const std::string refusal = overwriteRefusal(r, calibration_file_, pnh_.param("max_uncertainty", 0.002));
    if (!refusal.empty()) {
      res.success = false;
      res.message = refusal + "; " + r.message + target_note;
      ROS_WARN("%s", res.message.c_str());
      return res;
    }
    StoredCalibration stored;
    stored.base_frame = base;
    stored.child_frame = child_frame_;
    stored.result = r;
    const std::string archived = saveCalibration(stored, calibration_file_);
    res.file = calibration_file_;
    stored.file = calibration_file_;
    std::string urdf_note;
    try {
      saveCalibratedUrdf(model_, stored, urdf_file_);
      res.urdf_file = urdf_file_;
      urdf_note = "; calibrated URDF " + urdf_file_;
    } catch (const std::exception& e) {
      urdf_note = std::string("; calibrated URDF NOT written: ") + e.what() + " (the calibration itself is saved)";
    }
    std::string bag_note;
    if (recorder) {
      {
        std::lock_guard<std::mutex> lock(recorder_mutex_);
        recorder_.reset();
      }
      try {
        recorder->commit();
        bag_note = "; recorded to " + recorder->file();
      } catch (const std::exception& e) {
        bag_note = std::string("; bag NOT recorded: ") + e.what();
      }
    }
    const std::string pictures = r.samples.empty() ? "" : savePictures(last_pair, r.samples.back());
    publish(r, child_frame_);
    publishSampleMarkers(r);
    const Eigen::Vector3d t = r.fixed_point.translation();
    char b[256];
    std::snprintf(b, sizeof b, "; fixed point [%.4f %.4f %.4f] m; saved to %s", t.x(), t.y(), t.z(),
                  calibration_file_.c_str());
    res.message = r.message + target_note + b + (archived.empty() ? "" : " (previous kept as " + archived + ")") + urdf_note + bag_note +
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

Result CalibrationNode::runNet(imagenets::Executor& exec, const Progress& progress, int samples, int requested,
                               StereoPair* last_pair, DetectionTime* detection_time) {
  // The sample net's own outputs after each repetition: the stereo pair and the sample, for the
  // live detection images (its inner executor is idle between repetitions).
  const int samples_node = exec.net().findNode("samples");
  const auto* inner = dynamic_cast<const imagenets::InnerNet*>(exec.net().node(samples_node).block.get());
  // With a target: the until net (calibration_target.yaml) whose solve's result is fed back.
  const imagenets::Executor* until = samples > requested ? untilNet(exec) : nullptr;
  if (until && (until->net().findNode("solve") < 0 || until->net().findNode("result") < 0)) until = nullptr;
  std::mutex mutex;
  int done = 0;
  // The two detections of the current sample; their sub-nets run on one thread each (threads: 1),
  // so their CPU time is the whole detection's.
  imagenets::BlockStats left, right;
  auto feedback = [&](int k, const std::string& stage) {
    imagenets_calibration_msgs::CalibrateFeedback f;
    f.sample = k;
    f.samples = samples;
    f.stage = stage;
    return f;
  };
  const int observer = exec.addObserver([&](const imagenets::RunEvent& e) {
    std::lock_guard<std::mutex> lock(mutex);
    const bool in_sample = e.block.rfind("samples/", 0) == 0 && e.block.find('/', 8) == std::string::npos;
    if (e.kind == imagenets::RunEventKind::BlockStarted && progress && (in_sample || e.block == "solve")) {
      // Stage: the block that started (e.g. samples/move_arm, samples/grab, samples/left_detection, solve).
      progress(feedback(e.block == "solve" ? done : done + 1, e.block));
    } else if (e.kind == imagenets::RunEventKind::BlockFinished && e.block == "samples/left_detection") {
      left = e.stats;
    } else if (e.kind == imagenets::RunEventKind::BlockFinished && e.block == "samples/right_detection") {
      right = e.stats;
    } else if (e.kind == imagenets::RunEventKind::Repetition && e.block == "samples") {
      done = e.index;
      detection_time->wall += std::max(left.last_ms, right.last_ms) / 1000.0;  // both images in parallel
      detection_time->cpu += std::max(left.last_cpu_ms, right.last_cpu_ms) / 1000.0;
      const imagenets::BlockStats sample_left = left, sample_right = right;
      left = right = {};
      if (until && progress && e.index >= requested && e.index < samples &&
          until->stats("solve").status == imagenets::BlockStatus::Ok) {
        // The until net has just solved the samples so far: how certain the fixed point is now.
        if (const auto so_far = until->output<imagenets_calibration_msgs::CalibrationResult>("result.value")) {
          auto f = feedback(e.index, "uncertainty");
          fillBounds(f, fromMsg(*so_far));
          progress(f);
          ROS_INFO("after %d poses: 3 sigma %.3f mm / %.4f deg", e.index, 1000 * f.uncertainty,
                   f.uncertainty_rotation * 180 / M_PI);
        }
      }
      const imagenets::Executor* sample_net = inner ? inner->innerExecutor() : nullptr;
      if (!sample_net || e.stats.status != imagenets::BlockStatus::Ok) return;
      StereoPair pair;
      try {
        pair.left = sample_net->output<sensor_msgs::Image>("left_image.value");
        pair.right = sample_net->output<sensor_msgs::Image>("right_image.value");
        pair.left_info = sample_net->output<sensor_msgs::CameraInfo>("left_info.value");
        pair.right_info = sample_net->output<sensor_msgs::CameraInfo>("right_info.value");
        const auto sample = sample_net->output<imagenets_calibration_msgs::CalibrationSample>("sample.value");
        if (!pair.left || !pair.right || !pair.left_info || !pair.right_info || !sample) return;
        const Sample s = fromMsg(*sample);
        publishDetections(pair, s);
        record(pair, s);
        *last_pair = pair;
        ROS_INFO("sample %d/%d: left %s (conf %.2f, %.0f ms, CPU %.0f ms), right %s (conf %.2f, %.0f ms, CPU %.0f ms)",
                 done, samples, s.left.found ? "found" : "not found", s.left.confidence, sample_left.last_ms,
                 sample_left.last_cpu_ms, s.right.found ? "found" : "not found", s.right.confidence,
                 sample_right.last_ms, sample_right.last_cpu_ms);
      } catch (const std::exception&) {
        // A sample net without these outputs (e.g. the replay's) draws no pictures.
      }
    }
  });
  running_ = &exec;
  imagenets::RunReport report;
  try {
    report = exec.runAll();
  } catch (...) {
    running_ = nullptr;
    exec.removeObserver(observer);
    throw;
  }
  running_ = nullptr;
  exec.removeObserver(observer);
  if (report.cancelled) throw std::runtime_error("cancelled (after " + std::to_string(done) + " samples)");
  const auto result = exec.output<imagenets_calibration_msgs::CalibrationResult>("result.value");
  if (!report.ok()) throw std::runtime_error(exec.net().origin() + ": " + report.failed.front());
  if (!result) throw std::runtime_error(exec.net().origin() + ": the net gave no result");
  return fromMsg(*result);
}

std::string CalibrationNode::savePictures(const StereoPair& pair, const Sample& sample) {
  // The last stereo pair with the detected marker points drawn, beside the calibration file.
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
  auto calibrated = std::make_shared<const RobotModel>(calibratedModel(model_, result));
  std::lock_guard<std::mutex> lock(calibration_mutex_);
  current_ = result.fixed_point;
  calibrated_model_ = std::move(calibrated);
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
  std::shared_ptr<const RobotModel> calibrated;  // publish(result) made it
  {
    std::lock_guard<std::mutex> lock(calibration_mutex_);
    calibrated = calibrated_model_;
  }
  for (size_t i = 0; i < result.samples.size(); ++i) {
    Sample s = result.samples[i];
    if (s.head_q.size() != 2 || s.arm_q.size() != model_.description().arm.joints.size()) continue;
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

}  // namespace imagenets_calibration
