#include "calibration_client.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "imagenets_calibration/calibration.h"
#include "friend_hw_sim/true_robot.h"
#include "friend_msgs/SetTrueRobot.h"
#include "imagenets/vision/frames.h"
#include "imagenets/package_file.h"

namespace imagenets {
namespace tool {

struct CalibrationClient::Impl {
  std::unique_ptr<ros::NodeHandle> nh;
  std::unique_ptr<ros::AsyncSpinner> spinner;
  ros::Subscriber head_base_sub, left_sub, joints_sub;
  std::mutex m;
  geometry_msgs::TransformStampedConstPtr head_base, left;
  sensor_msgs::JointStateConstPtr joints;
  std::unique_ptr<robot_description::RobotModel> nominal;
};

CalibrationClient::CalibrationClient(const std::string& name, double timeout) : impl_(new Impl) {
  if (!ros::isInitialized()) ros::init(ros::M_string(), name, ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  impl_->nh = std::make_unique<ros::NodeHandle>();
  impl_->spinner = std::make_unique<ros::AsyncSpinner>(1);
  impl_->spinner->start();
  Impl* p = impl_.get();
  p->head_base_sub = p->nh->subscribe<geometry_msgs::TransformStamped>(
      "/friend_sim/ground_truth/head_base", 2, [p](const geometry_msgs::TransformStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(p->m);
        p->head_base = m;
      });
  p->left_sub = p->nh->subscribe<geometry_msgs::TransformStamped>(
      "/friend_sim/ground_truth/left_camera", 2, [p](const geometry_msgs::TransformStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(p->m);
        p->left = m;
      });
  p->joints_sub = p->nh->subscribe<sensor_msgs::JointState>(
      "/friend_sim/ground_truth/joint_states", 2, [p](const sensor_msgs::JointStateConstPtr& m) {
        std::lock_guard<std::mutex> l(p->m);
        p->joints = m;
      });
  // The robot the simulator runs (its ~description), for the error's effective fixed point.
  std::string description = imagenets::packageFile("friend_description", "config/robot.yaml");
  ros::param::get("/friend_sim/description", description);
  p->nominal = std::make_unique<robot_description::RobotModel>(robot_description::loadRobotDescription(description));
  if (!ros::service::waitForService("/friend_calibration/calibrate", ros::Duration(timeout))) {
    throw std::runtime_error("service /friend_calibration/calibrate is not available after " + std::to_string(timeout) +
                             " s (is the calibration node running?)");
  }
}

CalibrationClient::~CalibrationClient() {
  if (impl_->spinner) impl_->spinner->stop();
}

std::string CalibrationClient::setTrueRobot(int seed, double magnitude) {
  friend_msgs::SetTrueRobot srv;
  srv.request.seed = seed;
  srv.request.magnitude = magnitude;
  if (!ros::service::waitForService("/friend_sim/set_true_robot", ros::Duration(10)) ||
      !ros::service::call("/friend_sim/set_true_robot", srv)) {
    throw std::runtime_error("the call of /friend_sim/set_true_robot failed (is friend_sim_node running?)");
  }
  if (!srv.response.success) throw std::runtime_error(srv.response.message);
  Impl* p = impl_.get();
  std::lock_guard<std::mutex> l(p->m);
  p->head_base.reset();  // the next comparison waits for the new truth
  p->left.reset();
  p->joints.reset();
  return srv.response.message;
}

const robot_description::RobotModel& CalibrationClient::nominal() const { return *impl_->nominal; }

void CalibrationClient::setSimParam(const std::string& name, double value) { ros::param::set("/friend_sim/" + name, value); }

CalibrationRun CalibrationClient::calibrate(int redundancy, const std::string& method, int poses) {
  imagenets_calibration_msgs::Calibrate::Request request;
  request.redundancy = redundancy;
  request.method = method;
  request.poses = poses;
  return calibrate(request);
}

CalibrationRun CalibrationClient::calibrate(const imagenets_calibration_msgs::Calibrate::Request& request) {
  CalibrationRun run;
  imagenets_calibration_msgs::Calibrate srv;
  srv.request = request;
  const auto start = std::chrono::steady_clock::now();
  if (!ros::service::call("/friend_calibration/calibrate", srv)) {
    throw std::runtime_error("the call of /friend_calibration/calibrate failed (node died?)");
  }
  run.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.response = srv.response;
  const auto& q = srv.response.fixed_point.transform.rotation;
  if (q.x == 0 && q.y == 0 && q.z == 0 && q.w == 0) return run;  // a failure before any result: nothing to compare
  run.fixed_point = frames::toIsometry(srv.response.fixed_point.transform, "response fixed_point");
  run.bound3_mm = 1000 * srv.response.uncertainty;
  run.bound3_deg = srv.response.uncertainty_rotation * 180 / M_PI;
  run.refused = !srv.response.success && srv.response.message.find("~max_uncertainty") != std::string::npos;
  // Ground truth (simulator only): wait briefly for fresh messages.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(1.0);
  Impl* p = impl_.get();
  while (ros::WallTime::now() < end) {
    {
      std::lock_guard<std::mutex> l(p->m);
      if (p->head_base) break;
    }
    ros::WallDuration(0.01).sleep();
  }
  std::lock_guard<std::mutex> l(p->m);
  if (!p->head_base) return run;
  run.have_truth = true;
  run.truth = frames::toIsometry(p->head_base->transform, "ground truth head_base");
  // The pan encoder's zero offset turns the whole head about the mount's z: folded into the
  // "effective" fixed point (no calibration of this frame can separate the two).
  std::string error_file;
  int seed = -1;
  double magnitude = 1.0;
  run.effective = run.identifiable = run.truth;
  if (ros::param::get("/friend_sim/true_error", error_file)) {
    ros::param::get("/friend_sim/seed", seed);
    ros::param::get("/friend_sim/magnitude", magnitude);
    try {
      const auto error = friend_hw_sim::loadTrueError(error_file, p->nominal->description(), seed, magnitude);
      run.effective = friend_hw_sim::effectiveHeadBase(p->nominal->description(), error);
      run.identifiable = friend_hw_sim::identifiableHeadBase(p->nominal->description(), error);
    } catch (const std::exception&) {
    }
  }
  run.error_mm = (run.fixed_point.translation() - run.truth.translation()).norm() * 1000;
  run.error_deg = imagenets_calibration::angleBetween(run.fixed_point, run.truth) * 180 / M_PI;
  run.effective_error_mm = (run.fixed_point.translation() - run.effective.translation()).norm() * 1000;
  run.effective_error_deg = imagenets_calibration::angleBetween(run.fixed_point, run.effective) * 180 / M_PI;
  run.identifiable_error_mm = (run.fixed_point.translation() - run.identifiable.translation()).norm() * 1000;
  run.identifiable_error_deg = imagenets_calibration::angleBetween(run.fixed_point, run.identifiable) * 180 / M_PI;
  return run;
}

}  // namespace tool
}  // namespace imagenets
