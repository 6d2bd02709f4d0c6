// Shared by `imagenets calibrate`, `imagenets repeatability` and `imagenets accuracy-study`: calls the running
// friend_calibration node and, when the simulator is running, compares with its ground truth.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "imagenets_calibration_msgs/Calibrate.h"
#include "robot_description/robot_model.h"

namespace imagenets {
namespace tool {

struct CalibrationRun {
  imagenets_calibration_msgs::Calibrate::Response response;
  bool have_truth = false;
  Eigen::Isometry3d fixed_point = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();      // simulator's true head mount
  Eigen::Isometry3d effective = Eigen::Isometry3d::Identity();  // true mount with the pan zero offset
  // The effective mount with arm joint 1's zero offset folded in too: what images can determine
  // (friend_hw_sim::identifiableHeadBase).
  Eigen::Isometry3d identifiable = Eigen::Isometry3d::Identity();
  double error_mm = 0, error_deg = 0, effective_error_mm = 0, effective_error_deg = 0;
  double identifiable_error_mm = 0, identifiable_error_deg = 0;
  // The reported uncertainty of the fixed point (joint method's pixel-level fit): the response's
  // 3-sigma bounds (3 sqrt(trace) of the covariance's translation and rotation blocks); 0 when none.
  double bound3_mm = 0, bound3_deg = 0;
  bool refused = false;  // computed, but the node kept its saved calibration (~max_uncertainty)
  double wall_time = 0;  // s, the service call
};

class CalibrationClient {
 public:
  // Initialises ROS (anonymous node `name`) if needed; waits up to `timeout` s for the service.
  CalibrationClient(const std::string& name, double timeout);
  ~CalibrationClient();
  // `poses` > 0: that many samples (the request's `poses`), else redundancy x the node's poses per loop.
  CalibrationRun calibrate(int redundancy, const std::string& method, int poses = 0);
  // Any request (e.g. with an uncertainty target).
  CalibrationRun calibrate(const imagenets_calibration_msgs::Calibrate::Request& request);
  // Simulator only: makes it run another true robot (friend_sim/set_true_robot: `seed` > 0 draws
  // the random error of true_error.yaml's magnitudes times `magnitude`). Returns its message;
  // throws with it when the simulator refuses or is not there. Later runs compare with that truth.
  std::string setTrueRobot(int seed, double magnitude);
  // The robot the simulator runs, as described (its ~description; FRIEND's when there is none).
  const robot_description::RobotModel& nominal() const;
  // Reads a float parameter of the simulator (or sets it); false when absent.
  static void setSimParam(const std::string& name, double value);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tool
}  // namespace imagenets
