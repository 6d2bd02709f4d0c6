#include "friend_hw_sim/friend_sim.h"

#include <cmath>
#include <cstdio>

#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <sensor_msgs/JointState.h>

#include "friend_hw_sim/cameras.h"
#include "friend_hw_sim/true_robot.h"
#include "imagenets/vision/frames.h"
#include "robot_description/urdf_writer.h"
#include "imagenets/package_file.h"

namespace friend_hw_sim {

using robot_description::loadRobotDescription;

FriendSim::FriendSim(ros::NodeHandle nh, ros::NodeHandle pnh)
    : nh_(nh),
      pnh_(pnh),
      nominal_(loadRobotDescription(pnh.param<std::string>("description", imagenets::packageFile("friend_description", "config/robot.yaml")))),
      true_error_file_(pnh.param<std::string>("true_error", imagenets::packageFile("friend_hw_sim", "config/true_error.yaml"))),
      truth_(std::make_shared<const robot_description::RobotModel>(
          applyTrueError(nominal_.description(),
                         loadTrueError(true_error_file_, nominal_.description(), pnh.param<int>("seed", -1),
                                       pnh.param("magnitude", 1.0))))),
      rng_(static_cast<unsigned>(pnh.param<int>("noise_seed", 1))) {
  time_scale_ = pnh_.param("time_scale", 1.0);
  if (!(time_scale_ > 0)) throw std::runtime_error("parameter ~time_scale must be positive");
  const auto& d = nominal_.description();
  head_link0_ = robot_description::urdfChainMountJoint(d, d.head).child;  // as the URDF TF comes from names it
  // ~move_joints false: only the standard interfaces (a robot without FRIEND's MoveJoints).
  const bool serve_move_joints = pnh_.param("move_joints", true);
  const auto group = [&](const std::string& name, const robot_description::KinematicChain& chain, unsigned seed_offset) {
    JointGroupConfig c;
    // A chain without joints (a camera on a stand) has no controller to serve.
    if (serve_move_joints && !chain.joints.empty()) c.move_action = name + "/move_joints";
    if (!chain.joints.empty()) c.trajectory_action = name + "_controller/follow_joint_trajectory";
    c.controller = name + "_controller";
    c.abort_probability_param = pnh_.resolveName("faults/" + name + "_abort_probability");
    c.settle_joint_param = pnh_.resolveName("faults/settle_joint");
    c.settle_error_param = pnh_.resolveName("faults/settle_error");
    c.seed = static_cast<unsigned>(pnh.param<int>("noise_seed", 1)) + seed_offset;
    return c;
  };
  arm_ = std::make_unique<JointGroupServer>(nh_, group("arm", d.arm, 11), d.arm, d.arm_home);
  head_ = std::make_unique<JointGroupServer>(nh_, group("head", d.head, 23), d.head, d.head_home);
  arm_->setTimeScale(time_scale_);
  head_->setTimeScale(time_scale_);
  joint_states_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  truth_joint_states_ = pnh_.advertise<sensor_msgs::JointState>("ground_truth/joint_states", 10);
  wrench_ = nh_.advertise<geometry_msgs::WrenchStamped>("ft_sensor/wrench", 10);
  for (const char* f : {"tcp", "marker", "left_camera", "right_camera", "head_base", "hand_camera"}) {
    truth_frames_[f] = pnh_.advertise<geometry_msgs::TransformStamped>(std::string("ground_truth/") + f, 10);
  }
  set_object_ = nh_.advertiseService("world_model/set", &FriendSim::setObject, this);
  get_object_ = nh_.advertiseService("world_model/get", &FriendSim::getObject, this);
  set_true_robot_ = pnh_.advertiseService("set_true_robot", &FriendSim::setTrueRobot, this);
  cameras_ = std::make_unique<CameraSim>(nh_, pnh_, *this);
  const double rate = pnh_.param("joint_state_rate", 50.0);
  last_tick_ = ros::Time::now();
  timer_ = nh_.createTimer(ros::Duration(1.0 / rate), &FriendSim::tick, this);
  ROS_INFO("friend_sim: %s, time_scale %.2f; true head mount differs from nominal by %.1f mm",
           d.source.c_str(), time_scale_,
           (truth_->headBase().translation() - nominal_.headBase().translation()).norm() * 1000);
}

FriendSim::~FriendSim() { timer_.stop(); }

std::shared_ptr<const robot_description::RobotModel> FriendSim::truth() const {
  std::lock_guard<std::mutex> lock(truth_mutex_);
  return truth_;
}

bool FriendSim::setTrueRobot(friend_msgs::SetTrueRobot::Request& req, friend_msgs::SetTrueRobot::Response& res) {
  const double magnitude = req.magnitude == 0 ? 1.0 : req.magnitude;
  std::shared_ptr<const robot_description::RobotModel> next;
  try {
    next = std::make_shared<const robot_description::RobotModel>(
        applyTrueError(nominal_.description(), loadTrueError(true_error_file_, nominal_.description(), req.seed, magnitude)));
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("set_true_robot: ") + e.what() + "; the true robot is unchanged";
    return true;
  }
  {
    std::lock_guard<std::mutex> lock(truth_mutex_);
    truth_ = next;
  }
  // Whoever derives something from the true robot's settings (e.g. a study's effective fixed
  // point) reads them where a launch file puts them.
  pnh_.setParam("seed", static_cast<int>(req.seed));
  pnh_.setParam("magnitude", magnitude);
  const Eigen::Isometry3d head_base = next->headBase();
  res.head_base = imagenets::frames::toTransformStamped(head_base, nominal_.description().base_frame,
                                                        head_link0_, ros::Time::now());
  char b[256];
  std::snprintf(b, sizeof b, "true robot: seed %d, magnitude %.2f; head mount %.1f mm, %.2f deg off the nominal one",
                static_cast<int>(req.seed), magnitude,
                (head_base.translation() - nominal_.headBase().translation()).norm() * 1000,
                Eigen::AngleAxisd(nominal_.headBase().linear().transpose() * head_base.linear()).angle() * 180 / M_PI);
  res.success = true;
  res.message = b;
  ROS_INFO("friend_sim: %s", b);
  return true;
}

RobotState FriendSim::state() const {
  RobotState s;
  s.stamp = ros::Time::now();
  s.arm = arm_->positions();
  s.head = head_->positions();
  s.arm_moving = arm_->moving();
  s.head_moving = head_->moving();
  return s;
}

void FriendSim::tick(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  // The time scale may change while running (the repeatability study times some runs at real speed).
  double scale = time_scale_;
  if (pnh_.getParamCached("time_scale", scale) && scale != time_scale_) {
    if (scale > 0) {
      ROS_INFO("friend_sim: time_scale %.2f -> %.2f", time_scale_, scale);
      time_scale_ = scale;
      arm_->setTimeScale(scale);
      head_->setTimeScale(scale);
    } else {
      ROS_WARN_THROTTLE(10, "friend_sim: ignoring ~time_scale %.3f (must be positive); keeping %.2f", scale, time_scale_);
    }
  }
  const double dt = std::max(0.0, (now - last_tick_).toSec()) * time_scale_;
  last_tick_ = now;
  arm_->step(dt);
  head_->step(dt);
  RobotState s = state();
  s.stamp = now;

  sensor_msgs::JointState js;
  js.header.stamp = now;
  js.name = arm_->names();
  for (const auto& n : head_->names()) js.name.push_back(n);
  js.position = s.arm;
  js.position.insert(js.position.end(), s.head.begin(), s.head.end());
  js.velocity = arm_->velocities();
  const auto hv = head_->velocities();
  js.velocity.insert(js.velocity.end(), hv.begin(), hv.end());
  for (double& v : js.velocity) v *= time_scale_;  // per second of simulated time -> per second of the clock
  truth_joint_states_.publish(js);
  double noise = 0;
  pnh_.getParamCached("encoder_noise", noise);
  if (noise > 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::normal_distribution<double> g(0.0, noise);
    for (double& p : js.position) p += g(rng_);
  }
  joint_states_.publish(js);
  publishGroundTruth(s);
  publishWrench(s);
}

void FriendSim::publishGroundTruth(const RobotState& s) {
  const auto model = truth();  // one true robot for all frames of this tick
  const auto& d = model->description();
  const std::string& base = d.base_frame;
  auto pub = [&](const char* key, const Eigen::Isometry3d& t, const std::string& child) {
    auto& p = truth_frames_[key];
    if (p.getNumSubscribers() > 0) p.publish(imagenets::frames::toTransformStamped(t, base, child, s.stamp));
  };
  pub("tcp", model->tcp(s.arm), d.tool.frame);
  pub("marker", model->marker(s.arm), d.marker.frame);
  pub("hand_camera", model->handCamera(s.arm), d.hand_camera.frame);
  pub("left_camera", model->leftCamera(s.head), d.left_camera.frame);
  pub("right_camera", model->rightCamera(s.head), d.right_camera_frame);
  pub("head_base", model->headBase(), head_link0_);
}

void FriendSim::publishWrench(const RobotState& s) {
  // Gravity of the payload hanging on the sensor, expressed in the (true) sensor frame.
  double mass = 0.8, fn = 0.05, tn = 0.005;
  std::vector<double> com{0.0, 0.0, 0.09};
  pnh_.getParamCached("ft_sensor/payload_mass", mass);
  pnh_.getParamCached("ft_sensor/force_noise", fn);
  pnh_.getParamCached("ft_sensor/torque_noise", tn);
  pnh_.getParamCached("ft_sensor/payload_com", com);
  if (com.size() != 3) com = {0.0, 0.0, 0.09};
  const Eigen::Isometry3d sensor = truth()->ftSensor(s.arm);
  const Eigen::Vector3d f = sensor.linear().transpose() * Eigen::Vector3d(0, 0, -9.81 * mass);
  const Eigen::Vector3d tau = Eigen::Vector3d(com[0], com[1], com[2]).cross(f);
  geometry_msgs::WrenchStamped w;
  w.header.stamp = s.stamp;
  w.header.frame_id = nominal_.description().ft_sensor.frame;
  std::lock_guard<std::mutex> lock(mutex_);
  std::normal_distribution<double> g(0.0, 1.0);
  w.wrench.force.x = f.x() + fn * g(rng_);
  w.wrench.force.y = f.y() + fn * g(rng_);
  w.wrench.force.z = f.z() + fn * g(rng_);
  w.wrench.torque.x = tau.x() + tn * g(rng_);
  w.wrench.torque.y = tau.y() + tn * g(rng_);
  w.wrench.torque.z = tau.z() + tn * g(rng_);
  wrench_.publish(w);
}

bool FriendSim::setObject(friend_msgs::WorldModelSet::Request& req, friend_msgs::WorldModelSet::Response& res) {
  if (req.name.empty()) {
    res.success = false;
    res.message = "world_model/set: the object name is empty";
    return true;
  }
  const auto& q = req.pose.pose.orientation;
  const double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (std::abs(n - 1.0) > 1e-3) {
    res.success = false;
    res.message = "world_model/set: object '" + req.name + "' has a non-unit orientation quaternion (norm " +
                  std::to_string(n) + ")";
    return true;
  }
  if (req.pose.header.frame_id.empty()) req.pose.header.frame_id = nominal_.description().base_frame;
  std::lock_guard<std::mutex> lock(mutex_);
  const bool replaced = world_.count(req.name) > 0;
  world_[req.name] = req;
  res.success = true;
  res.message = (replaced ? "replaced '" : "stored '") + req.name + "'";
  return true;
}

bool FriendSim::getObject(friend_msgs::WorldModelGet::Request& req, friend_msgs::WorldModelGet::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& kv : world_) res.names.push_back(kv.first);
  if (req.name.empty()) {
    res.found = false;
    res.message = std::to_string(world_.size()) + " objects";
    return true;
  }
  const auto it = world_.find(req.name);
  res.found = it != world_.end();
  if (res.found) {
    res.pose = it->second.pose;
    res.description = it->second.description;
    res.message = "found '" + req.name + "'";
  } else {
    res.message = "world model has no object '" + req.name + "'";
  }
  return true;
}

}  // namespace friend_hw_sim
