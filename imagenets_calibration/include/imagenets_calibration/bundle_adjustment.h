// The joint calibration fitted at pixel level: a bundle adjustment (Ceres Solver) over the fixed
// point, the marker offset (TCP -> target frame) and the identifiable joint zero offsets, whose
// residuals are the target's points (the square marker's 8 defined points, or the corners of a
// printed target with their ids) projected through the arm, the head chain and the camera models
// (with their distortion) minus the detected points, in every image of the calibration's cameras
// (the stereo pair's two, or the mono camera's one: no stereo fusion is needed), under a robust
// (Huber) loss. Its covariance at the solution is the result's uncertainty. Plain Eigen types
// here: Ceres stays inside bundle_adjustment.cpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/observability.h"

namespace imagenets_calibration {

// A pinhole camera with OpenCV distortion: plumb_bob (k1 k2 p1 p2 k3) or rational_polynomial
// (k1 k2 p1 p2 k3 k4 k5 k6); fewer coefficients = the rest zero.
struct PinholeCamera {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  std::vector<double> distortion;
  // Distorted pixel of a point in the camera frame (z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const;
};
struct StereoCameras {
  PinholeCamera left, right;
};
// The stereo camera models of the robot description (its camera_info files); nullopt with the
// reason in `why` when a file cannot be read.
std::optional<StereoCameras> stereoCamerasOf(const robot_description::RobotDescription& description, std::string* why);

// One camera a calibration measures with: which of a sample's observations is its
// (Sample::observation), its model and image size, and where it sits on the head: the head
// chain's last link -> the rig's optical frame (the left camera's, or the mono camera's), then
// that frame -> this camera's (the right camera's stereo baseline; identity for the others).
struct CalibrationCamera {
  int observation = Sample::kLeft;
  PinholeCamera model;
  int width = 0, height = 0;
  Eigen::Isometry3d in_head = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d in_rig = Eigen::Isometry3d::Identity();
  // Base -> its optical frame, given base -> the head chain's last link.
  Eigen::Isometry3d pose(const Eigen::Isometry3d& head_end) const { return head_end * in_head * in_rig; }
};
// The cameras a calibration measures with: the stereo pair (left, right) or one camera.
struct CameraModels {
  std::vector<CalibrationCamera> cameras;
  CameraModels() = default;
  // The description's stereo pair with these models.
  CameraModels(const robot_description::RobotDescription& description, const StereoCameras& stereo);
};
// The calibration cameras of the description (its calibration_camera: the stereo pair, or the
// mono camera) from their camera_info files; nullopt with the reason in `why` when a file cannot
// be read.
std::optional<CameraModels> cameraModelsOf(const robot_description::RobotDescription& description, std::string* why);

// The marker's 8 defined points in its frame (outer then inner border corners, the detector's
// order, imagenets/vision/marker.h) for a marker of `size` with the border `border` * size wide.
std::vector<Eigen::Vector3d> markerDefinedPoints(double size, double border = 0.25);

struct BundleAdjustmentOptions {
  // Huber loss: residuals beyond this many noise sigmas count linearly (a disturbed corner).
  double huber_sigmas = 3.0;
  // A detection whose 8 points do not fit its own pose within this (RMS px through the camera
  // model) was made with another camera model or carries no real points: it is not used.
  double max_point_mismatch = 1.0;
  int max_iterations = 100;
  // px: the point noise; 0 = estimated from the residuals (a robust sigma).
  double noise_sigma = 0.0;
};

// The fit's solution (Estimate: fixed point, marker offset, full-length joint offsets) and its
// Uncertainty (calibration.h), and how the fit went.
struct BundleAdjustment : Estimate, Uncertainty {
  bool ok = false;
  std::string message;  // what was fitted, or why not
  // The images determine the fixed point: its 3-sigma translation bound is below the marker
  // offset's prior sigma. Not so with one relative motion (a single joint loop: the marker
  // offset's rotation about the motion's axis is free, 3 sigma ~0.5 m); the priors decide then.
  bool determined = false;
  double noise_sigma = 0.0;      // px, robust estimate of the point noise from the residuals
  int observations = 0;          // detections used (each camera's count separately)
  // Which parameters these detections determine, and the posterior covariance of all of them
  // (parameter order: fixed point, marker offset, arm offsets, head offsets as estimated).
  Observability observability;
};

// Starts from `start` (the joint method's solution: fixed point, marker offset, joint offsets) and
// fits the samples given (the joint method's used ones); a detection is used when `usable` says so
// and its points fit its pose (options.max_point_mismatch). Each detection's points are where its
// `object_points` say on the target (a target's corners with ids, imagenets_vision/target.h);
// detections without them are the square marker's defined points, `marker_points`.
BundleAdjustment bundleAdjust(const RobotModel& model, const CameraModels& cameras,
                              const std::vector<Eigen::Vector3d>& marker_points, const std::vector<const Sample*>& samples,
                              const Result& start, double max_reprojection_error,
                              const BundleAdjustmentOptions& options = {});

// What a plan of poses will determine before the robot moves: the bundle adjustment's
// observability at the nominal robot, each pose seen as the nominal geometry projects it (views
// where the marker leaves an image or turns its back do not count), with point noise `noise_px`.
Observability predictObservability(const RobotModel& model, const CameraModels& cameras,
                                   const std::vector<CalibrationPose>& poses, double noise_px);

}  // namespace imagenets_calibration
