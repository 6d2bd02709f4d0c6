// Shared by `imagenets calibrate` and `imagenets repeatability`: calls the running
// friend_calibration node and, when the simulator is running, compares with its ground truth.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "imagenets/Calibrate.h"

namespace imagenets {
namespace tool {

struct CalibrationRun {
  imagenets::Calibrate::Response response;
  bool have_truth = false;
  Eigen::Isometry3d fixed_point = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();      // simulator's true head mount
  Eigen::Isometry3d effective = Eigen::Isometry3d::Identity();  // true mount with the pan zero offset
  double error_mm = 0, error_deg = 0, effective_error_mm = 0, effective_error_deg = 0;
  double wall_time = 0;  // s, the service call
};

class CalibrationClient {
 public:
  // Initialises ROS (anonymous node `name`) if needed; waits up to `timeout` s for the service.
  CalibrationClient(const std::string& name, double timeout);
  ~CalibrationClient();
  CalibrationRun calibrate(int redundancy, const std::string& method);
  // Reads a float parameter of the simulator (or sets it); false when absent.
  static void setSimParam(const std::string& name, double value);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tool
}  // namespace imagenets
