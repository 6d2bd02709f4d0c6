// The solvers everybody has, for comparison with ours: OpenCV's hand-eye methods (calibrateHandEye:
// Tsai, Park, Horaud, Andreff, Daniilidis; calibrateRobotWorldHandEye: Shah, Li), which
// easy_handeye and moveit_calibration call, set up for the eye-to-hand case: a camera that does not
// move during the samples and a target on the gripper. They take one pose per sample (the target
// in the camera, the TCP in the base), where our calibration fits the corners' pixels.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace imagenets_calibration {

struct HandEyeSample {
  Eigen::Isometry3d base_tcp = Eigen::Isometry3d::Identity();       // T_base_tcp (forward kinematics)
  Eigen::Isometry3d camera_target = Eigen::Isometry3d::Identity();  // T_camera_target (the detection's pose)
};

struct HandEyeSolution {
  std::string method;  // "Tsai", "Park", "Horaud", "Andreff", "Daniilidis", "Shah", "Li"
  bool ok = false;
  std::string error;   // why not (OpenCV's exception)
  Eigen::Isometry3d base_camera = Eigen::Isometry3d::Identity();  // T_base_camera
  // T_tcp_target: calibrateRobotWorldHandEye's own; for calibrateHandEye's methods, the mean over
  // the samples of T_tcp_base T_base_camera T_camera_target (rotation: chordal mean).
  Eigen::Isometry3d tcp_target = Eigen::Isometry3d::Identity();
};

// Every method on the same samples (at least 3, with rotations about different axes).
std::vector<HandEyeSolution> eyeToHandPeers(const std::vector<HandEyeSample>& samples);

}  // namespace imagenets_calibration
