#include "imagenets_calibration/calibration_node.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <boost/filesystem.hpp>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/net_wide_property.h"
#include "imagenets/package_file.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/target.h"
#include "imagenets_calibration/bag_samples.h"
#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets_calibration/robot_interfaces.h"

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

// The robot's description (~description), measured with the camera ~calibration_camera names
// (stereo or mono; not set: the description's own calibration_camera).
robot_description::RobotDescription describedRobot(const ros::NodeHandle& pnh) {
  auto d = robot_description::loadRobotDescription(requiredParam(pnh, "description", "the robot's description YAML"));
  const std::string camera = pnh.param<std::string>("calibration_camera", "");
  return camera.empty() ? d : robot_description::withCalibrationCamera(d, camera, "parameter " + pnh.resolveName("calibration_camera"));
}

std::string defaultCalibrationFile() {
  const char* ros_home = std::getenv("ROS_HOME");
  const char* home = std::getenv("HOME");
  const std::string dir = ros_home ? ros_home : std::string(home ? home : "/tmp") + "/.ros";
  return dir + ros::this_node::getName() + "/pth_fixed_point.yaml";
}

template <class Out>
void fill(Out& out, const Result& r, const std::string& base, const std::string& child) {
  summarize(toMsg(r, base, child), out);
  out.fixed_point.header.stamp = ros::Time::now();
  fillBounds(out, r);
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
      model_(describedRobot(pnh)),
      marker_(imagenets::marker::MarkerDescription::load(
          requiredParam(pnh, "marker", "the marker's description YAML"))) {
  readParameters();
  const std::string joint_states = pnh_.param<std::string>("joint_states", "joint_states");
  publisher_ = std::make_unique<CalibrationPublisher>(nh_, pnh_, model_, marker_.size, fusion_, child_frame_, joint_states);
  loadNetsReporting();
  checkControllers();
  setUpRecording(joint_states);
  publishStartupCalibration();
  startServices();
  ROS_INFO("%s: ready (%s, net %s, default redundancy %d, method %s, file %s)",
           ros::this_node::getName().c_str(), model_.description().source.c_str(), net_file_.c_str(), default_redundancy_, default_method_.c_str(),
           calibration_file_.c_str());
}

void CalibrationNode::readParameters() {
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
}

void CalibrationNode::loadNetsReporting() {
  // The nets, once. A bad net is reported (and every request answers with it); the node keeps
  // serving the previous calibration.
  net_file_ = requiredParam(pnh_, "net", "the calibration net");
  try {
    loadNets(net_file_, pnh_.param<std::string>("replay_net", imagenets::packageFile("imagenets_calibration", "config/nets/calibration_sample_replay.yaml")));
    publisher_->advertiseDetections(live_net_->cameras());
  } catch (const std::exception& e) {
    net_error_ = e.what();
    ROS_ERROR("%s: the calibration net is not usable: %s", ros::this_node::getName().c_str(), net_error_.c_str());
  }
}

void CalibrationNode::setUpRecording(const std::string& joint_states) {
  record_bag_ = pnh_.param<std::string>("record_bag", "");
  if (record_bag_.empty()) return;
  record_bag_ = boost::filesystem::absolute(record_bag_).string();
  const std::string& stereo = model_.description().stereo_namespace;
  record_camera_topic_ = nh_.resolveName(pnh_.param<std::string>("record_camera", stereo.empty() ? "stereo" : stereo));
  record_joint_states_topic_ = nh_.resolveName(joint_states);
  tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf", 100, [this](const tf2_msgs::TFMessageConstPtr& m) { onTf(m, false); });
  tf_static_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf_static", 100,
                                                      [this](const tf2_msgs::TFMessageConstPtr& m) { onTf(m, true); });
}

void CalibrationNode::publishStartupCalibration() {
  const std::string replay = pnh_.param<std::string>("replay", "");
  try {
    if (!replay.empty()) {
      Request req;
      req.replay = replay;
      req.method = default_method_;
      const auto res = run(req, {});
      if (!res.success) throw std::runtime_error(res.message);
      ROS_INFO("%s", res.message.c_str());
    } else if (std::ifstream(calibration_file_).good()) {
      const StoredCalibration stored = loadCalibration(calibration_file_);
      publisher_->publishCalibration(stored.result);
      publisher_->publishSampleMarkers(stored.result);
      ROS_INFO("loaded the calibration of %s from %s", stored.created.c_str(), calibration_file_.c_str());
    } else {
      ROS_WARN("no calibration yet (%s does not exist): publishing the nominal fixed point until calibrated",
               calibration_file_.c_str());
      publisher_->publishNominal();
    }
  } catch (const std::exception& e) {
    ROS_ERROR("%s: publishing the nominal fixed point", e.what());
    publisher_->publishNominal();
  }
}

void CalibrationNode::startServices() {
  service_ = pnh_.advertiseService("calibrate", &CalibrationNode::onService, this);
  action_ = std::make_unique<actionlib::SimpleActionServer<imagenets_calibration_msgs::CalibrateAction>>(
      pnh_, "calibrate_action", [this](const imagenets_calibration_msgs::CalibrateGoalConstPtr& g) { onAction(g); }, false);
  action_->registerPreemptCallback([this] { cancel(); });
  action_->start();
}

void CalibrationNode::loadNets(const std::string& net, const std::string& replay_net) {
  imagenets::NetSpec spec = imagenets::parseNetFile(net);
  // ~sample_net: the net's sample net replaced (e.g. calibration_sample_mono.yaml for one camera).
  const std::string sample_net = pnh_.param<std::string>("sample_net", "");
  if (!sample_net.empty()) {
    const std::string samples = "samples";  // calibration_net_interface.h: the repeated sample sub-net
    if (spec.findBlock(samples) == nullptr) {
      throw std::runtime_error(net + ": no block '" + samples + "' whose sample net ~sample_net could replace");
    }
    spec.block(samples).setProperty("net", boost::filesystem::absolute(sample_net).string());
  }
  live_ = std::make_unique<imagenets::Executor>(imagenets::Net::build(spec));
  live_net_ = std::make_unique<CalibrationNetInterface>(*live_);  // throws naming what the net lacks
  // The sample net must measure with the calibration camera: a stereo sample net gives a mono
  // calibration no observation at all (and the other way round).
  const auto& cameras = live_net_->cameras();
  const bool mono = model_.description().calibration_camera == "mono";
  const bool has_mono = std::find(cameras.begin(), cameras.end(), "mono") != cameras.end();
  if (!cameras.empty() && mono != has_mono) {
    std::string list;
    for (const auto& c : cameras) list += (list.empty() ? "" : ", ") + c;
    throw std::runtime_error(net + ": its sample net measures with the cameras " + list + ", the calibration camera is " +
                             model_.description().calibration_camera + " (~calibration_camera, or head.calibration_camera of " +
                             model_.description().source + "): set ~sample_net to a " +
                             model_.description().calibration_camera + " sample net" +
                             (mono ? " (imagenets_calibration's config/nets/calibration_sample_mono.yaml)" : ""));
  }
  // The replay twin: the same net, its sample sub-net replaced by the replay sample net.
  imagenets::NetSpec replay_spec = spec;
  replay_spec.block(live_net_->samplesBlock()).setProperty("net", replay_net);
  replay_ = std::make_unique<imagenets::Executor>(imagenets::Net::build(replay_spec));
  replay_net_ = std::make_unique<CalibrationNetInterface>(*replay_);
  setDescriptionAndTarget(net);
  // The robot's controllers and camera topics its description names, in place of the nets' own.
  for (const std::string& line : applyRobotInterfaces(model_.description(), *live_)) {
    ROS_INFO("%s: %s", live_->net().origin().c_str(), line.c_str());
  }
  applyRobotInterfaces(model_.description(), *replay_);
}

void CalibrationNode::checkControllers() {
  // Said at once rather than after a move block's server_timeout in the first calibration (which
  // then fails naming the action too); the node serves on: the controller may start later.
  for (const std::string& missing : missingControllers(model_.description(), pnh_.param("server_timeout", 10.0))) {
    ROS_ERROR("%s: %s", ros::this_node::getName().c_str(), missing.c_str());
  }
}

void CalibrationNode::setDescriptionAndTarget(const std::string& net) {
  // The robot this node calibrates, for every block of its nets (sub-nets included) that reads a
  // robot description from a path property `description`: their own default is FRIEND's.
  const std::string description = boost::filesystem::absolute(model_.description().source).string();
  for (imagenets::Executor* exec : {live_.get(), replay_.get()}) {
    const auto set = imagenets::setPropertyInNetTree(*exec, "description", description,
                                                     [](const imagenets::PropertySpec& p) { return p.isPath(); });
    ROS_DEBUG("%s: description %s set on %zu blocks", exec->net().origin().c_str(), description.c_str(), set.size());
    // The camera measured with, for the blocks that plan and solve with it (the node's own choice).
    imagenets::setPropertyInNetTree(*exec, "calibration_camera", model_.description().calibration_camera);
  }
  // What the gripper carries, when not the nets' own square marker: a target file (~target,
  // config/targets/ of imagenets_vision) for every block that reads one; the sample net's detection
  // (imagenets/TargetDetectionNet) runs the detection net of its kind with it.
  const std::string target = pnh_.param<std::string>("target", "");
  if (target.empty()) return;
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

void CalibrationNode::onTf(const tf2_msgs::TFMessageConstPtr& msg, bool is_static) {
  std::lock_guard<std::mutex> lock(recorder_mutex_);
  if (is_static) {
    for (const auto& t : msg->transforms) tf_static_[t.child_frame_id] = t;
  }
  if (recorder_) recorder_->write(is_static ? "/tf_static" : "/tf", ros::Time::now(), *msg);
}

void CalibrationNode::record(const CameraImages& images, const Sample& sample) {
  std::shared_ptr<BagRecorder> recorder;
  {
    std::lock_guard<std::mutex> lock(recorder_mutex_);
    recorder = recorder_;
  }
  if (!recorder || images.empty()) return;
  // The bag's topics as the camera and joint_states publish them; the joint readings are the ones
  // the sample used, stamped with its image, so the bag's sample is exactly this one.
  BagSampleSettings topics;
  topics.camera = record_camera_topic_;
  topics.joint_states = record_joint_states_topic_;
  const auto& stamp = images.front().image->header.stamp;
  const ros::Time t = stamp.isZero() ? ros::Time::now() : stamp;
  for (const CameraImage& c : images) {
    recorder->write(topics.imageTopic(c.camera), t, *c.image);
    recorder->write(topics.infoTopic(c.camera), t, *c.info);
  }
  sensor_msgs::JointState joints;
  joints.header.stamp = stamp;
  joints.name = sampleJoints(model_);
  joints.position = sample.arm_q;
  joints.position.insert(joints.position.end(), sample.head_q.begin(), sample.head_q.end());
  recorder->write(topics.jointStatesTopic(), t, joints);
}

bool CalibrationNode::onService(Request& req, Response& res) {
  res = run(req, {});
  return true;
}

void CalibrationNode::cancel() {
  if (imagenets::Executor* exec = running_.load()) exec->cancel();
}

void CalibrationNode::onAction(const imagenets_calibration_msgs::CalibrateGoalConstPtr& goal) {
  Request req;
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
  Response res;
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

std::string CalibrationNode::claim(const Request& req, int redundancy, const std::string& method) {
  // One lock for the flag and its description: triggers arrive on several spinner threads at once.
  std::lock_guard<std::mutex> lock(busy_mutex_);
  if (busy_) return "rejected: a calibration is already running (" + busy_with_ + "); try again when it has finished";
  busy_ = true;
  busy_with_ = (req.replay.empty() ? req.poses > 0 ? std::to_string(req.poses) + " poses" : "redundancy " + std::to_string(redundancy)
                                   : "replay of " + req.replay) +
               (req.target_uncertainty > 0 || req.target_uncertainty_rotation > 0 ? " until certain" : "") +
               ", method " + method + ", started " + utcStamp(true);
  return "";
}

void CalibrationNode::checkRequest(const Request& req, const std::string& method) {
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
}

CalibrationNode::PoseCounts CalibrationNode::configureNet(const CalibrationNetInterface& net, const Request& req,
                                                          int redundancy, const std::string& method) {
  imagenets::Executor& exec = net.executor();
  exec.setProperty("plan", "method", method);
  exec.setProperty("plan", "replay", req.replay.empty() ? std::string() : boost::filesystem::absolute(req.replay).string());
  exec.setProperty("plan", "loops", redundancy);
  exec.setProperty("plan", "poses_per_loop", poses_per_loop_);
  exec.setProperty("plan", "poses", static_cast<int>(req.poses));
  PoseCounts poses;
  poses.requested = !req.replay.empty() ? 0
                    : req.poses > 0     ? static_cast<int>(req.poses)
                                        : redundancy * (method == "joint" ? std::max(1, poses_per_loop_) : 1);
  poses.max_poses = req.max_poses > 0 ? static_cast<int>(req.max_poses) : std::max(max_poses_, poses.requested);
  const bool target = req.target_uncertainty > 0 || req.target_uncertainty_rotation > 0;
  poses.total = target ? poses.max_poses : poses.requested;
  exec.setProperty("plan", "target_uncertainty", static_cast<double>(req.target_uncertainty));
  exec.setProperty("plan", "target_uncertainty_rotation", static_cast<double>(req.target_uncertainty_rotation));
  exec.setProperty("plan", "max_poses", std::max(1, poses.max_poses));
  // The solve's limits, for the net's solve and for the one that decides whether a target is met.
  imagenets::Executor* until = net.untilNet();
  for (imagenets::Executor* e : {&exec, until}) {
    if (!e || e->net().findNode("solve") < 0) continue;
    e->setProperty("solve", "max_position_difference", fusion_.max_position_difference);
    e->setProperty("solve", "max_angle_difference", fusion_.max_angle_difference);
    e->setProperty("solve", "min_valid_fraction", min_valid_fraction_);
  }
  return poses;
}

std::shared_ptr<BagRecorder> CalibrationNode::startRecording(const Request& req) {
  // What a live calibration saw, into a bag put in place only when the calibration succeeds.
  if (record_bag_.empty() || !req.replay.empty()) return nullptr;
  auto recorder = std::make_shared<BagRecorder>(record_bag_);
  std::lock_guard<std::mutex> lock(recorder_mutex_);
  tf2_msgs::TFMessage statics;
  for (const auto& t : tf_static_) statics.transforms.push_back(t.second);
  if (!statics.transforms.empty()) recorder->write("/tf_static", ros::Time::now(), statics);
  recorder_ = recorder;
  return recorder;
}

imagenets_calibration_msgs::Calibrate::Response CalibrationNode::run(const Request& req, const Progress& progress) {
  Response res;
  const int n = req.redundancy > 0 ? req.redundancy : default_redundancy_;
  const std::string method = req.method.empty() ? default_method_ : req.method;
  res.message = claim(req, n, method);
  if (!res.message.empty()) return res;
  struct Release {
    std::atomic<bool>& b;
    ~Release() { b = false; }
  } release{busy_};
  struct StopRecording {
    std::mutex& m;
    std::shared_ptr<BagRecorder>& r;
    ~StopRecording() {
      std::lock_guard<std::mutex> lock(m);
      r.reset();
    }
  } stop_recording{recorder_mutex_, recorder_};
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  try {
    if (!net_error_.empty()) throw std::runtime_error("the calibration net is not usable: " + net_error_);
    checkRequest(req, method);
    const CalibrationNetInterface& net = req.replay.empty() ? *live_net_ : *replay_net_;
    const PoseCounts poses = configureNet(net, req, n, method);
    const std::shared_ptr<BagRecorder> recorder = startRecording(req);
    const NetRun run = runNet(net, progress, poses);
    const Result& r = run.result;
    fill(res, r, model_.description().base_frame, child_frame_);
    res.target_met = r.withinUncertaintyTarget(req.target_uncertainty, req.target_uncertainty_rotation);
    const bool target = req.target_uncertainty > 0 || req.target_uncertainty_rotation > 0;
    const std::string target_note =
        target ? targetNote(res, req.target_uncertainty, req.target_uncertainty_rotation, poses.max_poses) : "";
    res.total_time = elapsed();
    if (!req.replay.empty()) {
      // Re-solved stored samples: no robot, nothing saved or published.
      res.message = "replay of " + std::to_string(r.samples.size()) + " stored samples from " + req.replay + ": " +
                    r.message;
      if (!r.success) res.message = "calibration failed: " + res.message;
      return res;
    }
    res.compute_time = r.compute_time + run.detection_time.wall;  // image processing + solving, no motion
    res.detection_cpu_time = run.detection_time.cpu;
    if (!r.success) {
      res.message = "calibration failed: " + r.message + target_note +
                    "; the saved calibration and the published frame are unchanged";
      return res;
    }
    saveAndPublish(run, recorder, target_note, res);
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("calibration failed: ") + e.what() +
                  "; the saved calibration and the published frame are unchanged";
    res.total_time = elapsed();
    ROS_WARN("%s", res.message.c_str());
  }
  return res;
}

void CalibrationNode::saveAndPublish(const NetRun& run, const std::shared_ptr<BagRecorder>& recorder,
                                     const std::string& target_note, Response& res) {
  const Result& r = run.result;
  const std::string refusal = overwriteRefusal(r, calibration_file_, pnh_.param("max_uncertainty", 0.002));
  if (!refusal.empty()) {
    res.success = false;
    res.message = refusal + "; " + r.message + target_note;
    ROS_WARN("%s", res.message.c_str());
    return;
  }
  StoredCalibration stored;
  stored.base_frame = model_.description().base_frame;
  stored.child_frame = child_frame_;
  stored.result = r;
  const std::string archived = saveCalibration(stored, calibration_file_);
  res.file = calibration_file_;
  stored.file = calibration_file_;
  std::string urdf_note;
  if (publisher_->writeUrdf(stored, urdf_file_, &urdf_note)) res.urdf_file = urdf_file_;
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
  const std::string pictures =
      r.samples.empty() ? "" : publisher_->savePictures(run.last_images, r.samples.back(), calibration_file_);
  publisher_->publishCalibration(r);
  publisher_->publishSampleMarkers(r);
  const Eigen::Vector3d t = r.fixed_point.translation();
  char b[256];
  std::snprintf(b, sizeof b, "; fixed point [%.4f %.4f %.4f] m; saved to %s", t.x(), t.y(), t.z(),
                calibration_file_.c_str());
  res.message = r.message + target_note + b + (archived.empty() ? "" : " (previous kept as " + archived + ")") + urdf_note + bag_note +
                (pictures.empty() ? "" : "; pictures: " + pictures);
  ROS_INFO("%s", res.message.c_str());
}

CalibrationNode::NetRun CalibrationNode::runNet(const CalibrationNetInterface& net, const Progress& progress,
                                                const PoseCounts& poses) {
  imagenets::Executor& exec = net.executor();
  auto watch = std::make_shared<CalibrationRunWatch>(
      net, poses.total, poses.requested, progress, [this](const CameraImages& images, const Sample& sample) {
        publisher_->publishDetections(images, sample);
        record(images, sample);
      });
  const int observer = exec.addObserver([watch](const imagenets::RunEvent& e) { (*watch)(e); });
  struct Detach {
    imagenets::Executor& exec;
    std::atomic<imagenets::Executor*>& running;
    int observer;
    ~Detach() {
      running = nullptr;
      exec.removeObserver(observer);
    }
  } detach{exec, running_, observer};
  running_ = &exec;
  const imagenets::RunReport report = exec.runAll();
  if (report.cancelled) throw std::runtime_error("cancelled (after " + std::to_string(watch->done()) + " samples)");
  const auto result = net.result();
  if (!report.ok()) throw std::runtime_error(exec.net().origin() + ": " + report.failed.front());
  if (!result) throw std::runtime_error(exec.net().origin() + ": the net gave no result");
  return {fromMsg(*result), watch->detectionTime(), watch->lastImages()};
}

}  // namespace imagenets_calibration
