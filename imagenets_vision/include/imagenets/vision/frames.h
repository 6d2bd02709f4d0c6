// Frame maths shared by the frames blocks, the calibration node and the simulator: message <->
// Eigen conversion with validity checks, quaternion mean (eigenvector method), per-axis median,
// classic Denavit-Hartenberg forward kinematics and the stereo pose fusion rule of the paper (4.2).
// Everything here is plain Eigen; the blocks in imagenets_blocks/frames/ are thin wrappers.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Vector3.h>

namespace imagenets {
namespace frames {

// A pose or transform that cannot be used (NaN, non-unit quaternion, bad DH table, ...). The
// message names the value (`what` argument of the conversions) and the problem.
struct FrameError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Quaternions whose norm differs from 1 by more than this are rejected (not silently
// normalised): such a value is almost always a bug upstream. Smaller deviations (rounding in
// YAML files) are normalised.
constexpr double kQuaternionNormTolerance = 1e-3;

// Conversions. `what` names the value in error messages ("input 'a'"). Throw FrameError on NaN /
// infinite components or a quaternion whose norm is not 1 (within kQuaternionNormTolerance).
Eigen::Quaterniond toQuaternion(const geometry_msgs::Quaternion& q, const std::string& what);
Eigen::Vector3d toVector(const geometry_msgs::Vector3& v, const std::string& what);
Eigen::Vector3d toVector(const geometry_msgs::Point& p, const std::string& what);
Eigen::Isometry3d toIsometry(const geometry_msgs::Pose& pose, const std::string& what);
Eigen::Isometry3d toIsometry(const geometry_msgs::Transform& transform, const std::string& what);

geometry_msgs::Quaternion toQuaternionMsg(const Eigen::Quaterniond& q);
geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v);
geometry_msgs::Point toPointMsg(const Eigen::Vector3d& v);
geometry_msgs::Pose toPose(const Eigen::Isometry3d& t);
geometry_msgs::Pose toPose(const geometry_msgs::Transform& t);  // the same numbers, unchecked
geometry_msgs::Transform toTransform(const Eigen::Isometry3d& t);
// parent -> child, stamped: what tf2 broadcasters and frame ports carry.
geometry_msgs::TransformStamped toTransformStamped(const Eigen::Isometry3d& t, const std::string& parent,
                                                   const std::string& child, const ros::Time& stamp);

// Angle (radians, 0..pi) of the rotation that takes a to b.
double rotationAngle(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// Mean rotation of a set by the eigenvector method (Markley et al. 2007): the eigenvector of the
// largest eigenvalue of M = sum w_i q_i q_i^T. Unlike averaging components, it is independent of
// the sign of each quaternion (q and -q are the same rotation) and is the rotation minimising the
// weighted sum of squared chordal distances. `weights` empty = all 1. Throws FrameError for an
// empty set, a negative weight or a weights/quaternions size mismatch. Result has w >= 0.
Eigen::Quaterniond meanRotation(const std::vector<Eigen::Quaterniond>& rotations,
                                const std::vector<double>& weights = {});

// Median of a set (mean of the two middle values for an even count). Throws FrameError if empty.
double median(std::vector<double> values);
// Per-axis median: x, y and z medians taken independently (robust to outliers in any axis).
Eigen::Vector3d medianTranslation(const std::vector<Eigen::Vector3d>& translations);

// Stereo fusion of two measurements of one pose (paper 4.2): when both are valid and agree within
// the limits, their mean (mean translation, eigenvector mean rotation); when only one is valid,
// that one; when they disagree or none is valid, invalid with the reason.
struct FusionLimits {
  double max_position_difference = 0.01;  // metres
  double max_angle_difference = 0.0873;   // radians (5 degrees)
};
struct FusionResult {
  enum class Source { Both, First, Second, None };
  bool valid = false;
  Source source = Source::None;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  double position_difference = 0;  // NaN unless both were valid
  double angle_difference = 0;     // radians; NaN unless both were valid
  std::string reason;              // why invalid (or which one was used)
};
FusionResult fusePoses(const std::optional<Eigen::Isometry3d>& first, const std::optional<Eigen::Isometry3d>& second,
                       const FusionLimits& limits);

}  // namespace frames
}  // namespace imagenets
