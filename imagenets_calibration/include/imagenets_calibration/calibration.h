// The FRIEND calibration (paper section 4): the pan-tilt head's fixed point ("PTH fixed point",
// base -> head_link_0, invariant under pan and tilt) from the gripper marker seen by the stereo
// camera. The functions read like the paper's Fig. 4.2 / 4.3 nets:
//
//   calibration pose -> gripperMarkerInRobot (arm forward kinematics + marker offset)
//   left / right image -> robust marker detection (calibration_marker_net.h) -> markerInLeftCamera
//   -> fuseStereoDetections -> leftCameraInRobot (invert) -> pthFixedPoint (head DH chain)
//   N samples -> combineRedundantSamples (mean rotation, per-axis median translation)
//
// Beyond the paper: every raw sample is kept with the result, per-sample residuals and rejected
// outliers are reported, and solveJointly() estimates the fixed point together with the marker
// offset from samples taken at different poses (robot-world / hand-eye least squares), which
// removes the bias a single pose inherits from the marker-offset and joint-offset errors.
// Plain Eigen (no ROS) so the node, the tool, the study and the tests share it.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "robot_description/robot_model.h"

namespace imagenets_calibration {

using robot_description::RobotModel;

// One marker (or target) detection in one camera image (the robust detection's result).
struct MarkerObservation {
  bool found = false;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // T_camera_marker
  double confidence = 0.0;
  double threshold = 0.0;            // binarisation threshold the feedback chose
  double reprojection_error = 0.0;   // RMS pixels
  std::vector<Eigen::Vector2d> points;  // the points found (distorted pixels): the square marker's 8
                                        // defined points, or a target's corners (imagenets_vision/target.h)
  std::vector<int> point_ids;           // their ids; empty: the square marker's 0..7
  std::vector<Eigen::Vector3d> object_points;  // each point on the target, its frame (m); empty: the
                                               // square marker's defined points of the description's size
  std::string reason;                // why not found
};

// One calibration sample: the raw measurements (kept, so a calibration can be re-solved without
// the robot) and what the paper's chain computes from them.
struct Sample {
  // Raw.
  std::vector<double> arm_q, head_q;  // joint_states (encoder readings) when the images were taken
  MarkerObservation left, right;      // the stereo pair's; right: in the right camera's own frame
  MarkerObservation mono;             // the head's mono camera's (calibration camera "mono")
  double stamp = 0.0;                 // image time, s
  // Camera i's observation (kLeft, kRight, kMono), each in its camera's own frame.
  static constexpr int kLeft = 0, kRight = 1, kMono = 2, kCameras = 3;
  static const char* cameraName(int i) { return i == kLeft ? "left" : i == kRight ? "right" : "mono"; }
  const MarkerObservation& observation(int i) const { return i == kLeft ? left : i == kRight ? right : mono; }
  MarkerObservation& observation(int i) { return i == kLeft ? left : i == kRight ? right : mono; }
  // Whether any camera found the target.
  bool seen() const { return left.found || right.found || mono.found; }
  // Derived (solveSample).
  bool valid = false;
  std::string reason;                 // why invalid, or which fusion source was used
  std::string fusion;                 // "both", "left", "right", "mono" or "none"
  // The target in the calibration camera's frame: the left one (fused with the right), or the mono one.
  Eigen::Isometry3d marker_in_left = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d fixed_point = Eigen::Isometry3d::Identity();     // this sample's estimate
};

// ---- Where the robot goes ---------------------------------------------------------------------

struct CalibrationPose {
  std::vector<double> arm, head;  // joint targets, rad
};

// The `count` poses a calibration visits. `paper`: the calibration pose every time (paper 4.2).
// `joint`: varied poses (wrist and elbow turned, the head following the marker), which its
// unknowns need.
std::vector<CalibrationPose> calibrationPoses(const RobotModel& model, int count, const std::string& method);

// ---- The paper's chain (Fig. 4.2) ----------------------------------------------------------

// Base -> gripper marker from the arm's forward kinematics and the marker offset (TCP -> marker;
// the nominal one from the robot description unless given).
Eigen::Isometry3d gripperMarkerInRobot(const RobotModel& model, const std::vector<double>& arm_q);
Eigen::Isometry3d gripperMarkerInRobot(const RobotModel& model, const std::vector<double>& arm_q,
                                       const Eigen::Isometry3d& marker_offset);
// The right camera's detection expressed in the left camera frame (stereo extrinsics).
Eigen::Isometry3d markerInLeftCamera(const RobotModel& model, const Eigen::Isometry3d& marker_in_right);

struct FusionLimits {
  double max_position_difference = 0.002;  // m: left and right must agree within this...
  double max_angle_difference = 0.0175;    // rad (1 deg) ...and this, else the sample is invalid
  // A detection whose corners fit its pose worse than this (RMS pixels) is not used: a clean
  // marker fits to a few hundredths of a pixel, one disturbed by a reflection to tenths.
  double max_reprojection_error = 0.15;
  // calibrate() tightens that limit to this factor times the median reprojection error of all the
  // calibration's detections (the camera's own noise level; 0 = off), but not below the floor:
  // a reflection that moves the corners by a tenth of a pixel still stands out.
  double relative_reprojection_error = 5.0;
  double min_reprojection_error = 0.06;
};
struct Fusion {
  bool valid = false;
  std::string source;  // "both", "left", "right", "none"
  std::string reason;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};
// Mean of both when both are valid and agree, the valid one when only one is, else invalid.
Fusion fuseStereoDetections(const std::optional<Eigen::Isometry3d>& left,
                            const std::optional<Eigen::Isometry3d>& right_in_left, const FusionLimits& limits);
// Base -> left optical frame: marker in base composed with the inverted marker-in-camera pose.
Eigen::Isometry3d leftCameraInRobot(const Eigen::Isometry3d& marker_in_robot, const Eigen::Isometry3d& marker_in_left);
// Base -> head_link_0: the calibration camera's pose moved back through the head's chain at (pan, tilt).
Eigen::Isometry3d pthFixedPoint(const RobotModel& model, const Eigen::Isometry3d& left_camera_in_robot,
                                const std::vector<double>& head_q);
// The nominal chain head_link_0 -> the calibration camera's optical frame (the left one of the
// pair, or the mono camera: the description's calibration_camera) at (pan, tilt).
Eigen::Isometry3d headChain(const RobotModel& model, const std::vector<double>& head_q);

// Runs the chain on one sample's raw data (the stereo pair's observations, fused, or the mono
// camera's, as the description's calibration_camera says); sets valid / reason / fusion / marker_in_left /
// fixed_point. `marker_offset`: TCP -> marker to use (nominal when not given).
void solveSample(const RobotModel& model, Sample& sample, const FusionLimits& limits,
                 const std::optional<Eigen::Isometry3d>& marker_offset = std::nullopt);

// ---- Redundancy (Fig. 4.3) and the combined result ----------------------------------------

struct CombineOptions {
  // A sample whose frame is further than max(floor, k * robust sigma) from the robust centre
  // (per-axis median translation, medoid rotation) is rejected as an outlier.
  double outlier_translation_floor = 0.003;  // m
  double outlier_rotation_floor = 0.0087;    // rad (0.5 deg)
  double outlier_sigmas = 4.0;
  int min_valid_samples = 1;                 // fewer valid (after rejection) -> failure
};

// What a calibration estimates (fixed point, target offset, joint zero offsets): one definition
// that the result and the pixel-level fit (bundle_adjustment.h) share, so the fit's solution is
// taken over as a whole, not field by field.
struct Estimate {
  Eigen::Isometry3d fixed_point = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d marker_offset = Eigen::Isometry3d::Identity();  // TCP -> marker used / estimated
  // Joint zero offsets estimated by the joint method (rad, added to the DH theta offsets; empty =
  // none). Arm joints 1 and 7 and the pan are not estimated: their offsets are indistinguishable
  // from a rotation of the fixed point, of the marker offset and of the fixed point about z.
  std::vector<double> arm_joint_offsets, head_joint_offsets;
};

// The uncertainty of an Estimate from the pixel-level fit: the covariance at the solution, scaled
// by the residual variance. Fixed point and marker offset: 6x6 over (translation m, rotation
// vector rad), perturbed on the left in the parent frame: X = (exp(w) R, t + dt). Joint offsets:
// standard deviations (rad, 0 = not estimated). All zero when not computed.
struct Uncertainty {
  bool has_covariance = false;
  Eigen::Matrix<double, 6, 6> fixed_point_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> marker_offset_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  std::vector<double> arm_joint_offset_std, head_joint_offset_std;
  double reprojection_rms = 0.0;  // px, the pixel-level fit's residual (0 = not fitted)
  // Observability at the solution (observability.h; computed with the covariance): the estimated
  // parameters the poses do not determine (posterior std > 0.5 x prior std; empty = all
  // determined), and the condition number of the Jacobian in units of the prior std (0 = not
  // computed, inf = a direction not observed at all).
  std::vector<std::string> unobservable;
  double condition_number = 0.0;
  // Per-parameter standard deviations: sqrt of the covariance's diagonal, (x, y, z m, rx, ry, rz
  // rad about the parent frame's axes); 0 for a parameter held at its nominal value.
  Eigen::Matrix<double, 6, 1> fixedPointStd() const { return fixed_point_covariance.diagonal().cwiseSqrt(); }
  Eigen::Matrix<double, 6, 1> markerOffsetStd() const { return marker_offset_covariance.diagonal().cwiseSqrt(); }
};

struct Result : Estimate, Uncertainty {
  bool success = false;
  std::string message;
  std::string method;  // "paper" or "joint"
  Eigen::Vector3d std_translation = Eigen::Vector3d::Zero();  // m, per axis, over the used samples
  Eigen::Vector3d std_rotation = Eigen::Vector3d::Zero();     // rad, rotation vector per axis
  std::vector<int> used, rejected;                            // sample indices
  std::vector<std::string> rejection_reasons;                 // parallel to `rejected`
  std::vector<double> residual_translation, residual_rotation;  // per sample (NaN when invalid)
  std::vector<Sample> samples;
  double compute_time = 0.0;  // s
  // One number each for the fixed point: sqrt(trace) of the translation / rotation block (m, rad);
  // the true error lies within 3 of it with high probability.
  double sigmaTranslation() const { return std::sqrt(fixed_point_covariance.topLeftCorner<3, 3>().trace()); }
  double sigmaRotation() const { return std::sqrt(fixed_point_covariance.bottomRightCorner<3, 3>().trace()); }
  // The Calibrate request's uncertainty target: whether this successful fit's 3-sigma bounds are
  // at most `translation` (m) and `rotation` (rad); a target <= 0 is not checked; false with
  // neither target set or without a covariance.
  bool withinUncertaintyTarget(double translation, double rotation) const {
    if (!success || !has_covariance || !(translation > 0 || rotation > 0)) return false;
    return (!(translation > 0) || 3 * sigmaTranslation() <= translation) &&
           (!(rotation > 0) || 3 * sigmaRotation() <= rotation);
  }
};

// The paper's redundancy (4.2): the mean rotation of all sample frames and the per-axis median of
// their translations, after rejecting invalid samples and outliers.
Result combineRedundantSamples(std::vector<Sample> samples, const CombineOptions& options);

// Beyond the paper: least squares over the fixed point X, the marker offset M and the zero offsets
// of the identifiable joints (arm 2..6, head tilt) such that for every used sample
//   X * headChain(head_q) * marker_in_left * p  =  tcp(arm_q) * M * p
// for the marker's corners and centre p (weak priors keep M and the offsets near nominal when the
// poses do not vary enough to observe them). Starts from `paper` (which also decides the outliers).
Result solveJointly(const RobotModel& model, const Result& paper, const FusionLimits& limits);

// The joint solution refined by the pixel-level bundle adjustment (bundle_adjustment.h) with the
// description's calibration camera models (the stereo pair or the mono camera), with its covariance; unchanged (the message says why) when
// the samples carry no points that fit those models.
void refineAtPixelLevel(const RobotModel& model, Result& joint, const FusionLimits& limits);

// Everything: solveSample on each sample, combine, and (method "joint") the joint solution,
// refined at pixel level.
// Throws std::invalid_argument for an unknown method.
Result calibrate(const RobotModel& model, std::vector<Sample> samples, const std::string& method,
                 const FusionLimits& limits, const CombineOptions& options);

// The model with joint zero offsets added to its DH theta offsets (empty vectors: unchanged).
RobotModel withJointOffsets(const RobotModel& model, const std::vector<double>& arm, const std::vector<double>& head);
// The nominal model with a calibration applied: the head's mount replaced by the fixed point, the
// marker offset by the estimated one, the estimated joint zero offsets added (the calibrated URDF
// is generated from it, storage.h).
RobotModel calibratedModel(const RobotModel& nominal, const Result& result);

// Rotation angle between two frames (rad) and the distance between their origins (m).
double angleBetween(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace imagenets_calibration
