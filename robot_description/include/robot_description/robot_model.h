// A robot's geometry, read once from its description file (config/friend/robot.yaml for FRIEND):
// classic DH chains for the arm and the pan-tilt head, fixed mounts, the gripper marker, the
// cameras; with forward kinematics. The one kinematics library: the simulator, the URDF
// generator, the blocks and the calibration all compute with it. Small (Eigen + yaml-cpp); the
// same chains read from a URDF are in urdf_kinematics.h (KDL, kept out of this header).
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace robot_description {

// One joint of a kinematic chain, the one form that DH rows and URDF joints both map onto:
//   T(link i-1 -> link i) = origin * Motion(axis, q + offset) * tip,
// Motion a rotation about `axis` by that angle (revolute) or a translation along it (prismatic).
// A classic DH row (fromDh): revolute: origin identity, axis z, offset theta_offset, tip
// Tz(d) Tx(a) Rx(alpha); prismatic: origin Rz(theta_offset), axis z, offset d, tip Tx(a) Rx(alpha).
// A URDF joint (urdf_kinematics.h): origin and axis as written, tip the fixed joints up to the next
// moving one. Estimated zero offsets (calibration, true-robot error) add to `offset`.
struct ChainJoint {
  std::string name;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity(), tip = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, in the frame after `origin`
  bool prismatic = false;
  double offset = 0;                                  // rad (m)
  double min = 0, max = 0, max_velocity = 0;          // rad (m), rad (m), rad/s (m/s)
};

// The forward kinematics of one joint at position q (its offset is added here): the one
// implementation, templated so that the calibration's bundle adjustment differentiates it with
// Ceres' dual numbers (T = double everywhere else). Written as constant 3x4 parts (double) times
// cos / sin of the angle (or the distance), so a dual number costs two products per entry:
//   revolute:  origin Rot(a, v) tip = M0 + cos(v) Mc + sin(v) Ms, with Rot = a a^T + c (I - a a^T) + s [a]x
//   prismatic: origin Trans(a v) tip = M0 + v Mv.
template <typename T>
Eigen::Matrix<T, 4, 4> jointMatrix(const ChainJoint& j, const T& q) {
  using std::cos;
  using std::sin;
  const T v = q + j.offset;
  const Eigen::Matrix3d ro = j.origin.linear();
  Eigen::Matrix<double, 3, 4> tip;
  tip << j.tip.linear(), j.tip.translation();
  Eigen::Matrix<double, 3, 4> m0, m1, m2 = Eigen::Matrix<double, 3, 4>::Zero();
  if (j.prismatic) {
    m0 = ro * tip;
    m1.setZero();
    m1.col(3) = ro * j.axis;
  } else {
    const Eigen::Matrix3d aat = j.axis * j.axis.transpose();
    Eigen::Matrix3d cross;
    cross << 0, -j.axis.z(), j.axis.y(), j.axis.z(), 0, -j.axis.x(), -j.axis.y(), j.axis.x(), 0;
    m0 = ro * aat * tip;
    m1 = ro * (Eigen::Matrix3d::Identity() - aat) * tip;
    m2 = ro * cross * tip;
  }
  m0.col(3) += j.origin.translation();
  const T f1 = j.prismatic ? v : T(cos(v)), f2 = j.prismatic ? T(0) : T(sin(v));
  Eigen::Matrix<T, 4, 4> m = Eigen::Matrix<T, 4, 4>::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = f1 * m1(r, c) + f2 * m2(r, c) + m0(r, c);
  }
  return m;
}

// One joint in the classic (distal, Denavit-Hartenberg 1955) convention, as description files
// write it:
//   T(i-1 -> i) = Rz(theta) Tz(d) Tx(a) Rx(alpha),
// theta = q + theta_offset for a revolute joint, d = q + d for a prismatic one. Metres, radians.
struct DhJoint {
  std::string name;
  double a = 0, alpha = 0, d = 0, theta_offset = 0;  // m, rad
  bool prismatic = false;
  double min = 0, max = 0, max_velocity = 0;          // rad (m), rad (m), rad/s (m/s)
};

// The DH row as a chain joint (see ChainJoint).
ChainJoint fromDh(const DhJoint& joint);
Eigen::Isometry3d dhTransform(const DhJoint& joint, double q);
// A DH table written as a flat list, 4 values per revolute joint in the textbook column order
// [d, theta offset, a, alpha, ...] (joints named joint_1..n, no limits). Throws
// std::invalid_argument if the size is not a positive multiple of 4 or a value is not finite.
std::vector<ChainJoint> parseDhTable(const std::vector<double>& flat);
// URDF meaning: Translation(xyz) * Rz(yaw) * Ry(pitch) * Rx(roll).
Eigen::Isometry3d fromXyzRpy(const Eigen::Vector3d& xyz, const Eigen::Vector3d& rpy);
// Inverse of the rotation part of fromXyzRpy (well defined at pitch = +-90 deg too).
Eigen::Vector3d rpyOf(const Eigen::Matrix3d& r);

// A serial chain hanging from the base: mount, then one ChainJoint per moving joint.
struct KinematicChain {
  std::string link_prefix;        // link i is link_prefix + i; link 0 is the mount's child
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // base -> link 0
  std::vector<ChainJoint> joints;  // none: a chain of fixed joints (a camera on a stand), all mount
  std::string tip_link;            // a URDF chain's last link as the URDF names it ("" for DH)
  std::vector<std::string> names() const;
  // Frames of links 0..n in the base frame (n + 1 entries). Throws std::invalid_argument if q has
  // the wrong size or a value is not finite.
  std::vector<Eigen::Isometry3d> linkFrames(const std::vector<double>& q) const;
  Eigen::Isometry3d end(const std::vector<double>& q) const { return linkFrames(q).back(); }
  // Empty when q is inside the limits; otherwise a sentence naming the joint, value and limits.
  std::string limitViolation(const std::vector<double>& q) const;
};

struct FixedFrame {
  std::string frame;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // relative to its parent
};

struct RobotDescription {
  std::string source;  // file it was loaded from (for messages)
  std::string name = "robot";  // the robot's name (key `name`): the generated URDF's <robot name>
  std::string base_frame = "base_link";
  KinematicChain arm, head;
  FixedFrame tool;         // arm last link -> TCP
  FixedFrame marker;       // TCP -> marker centre (z out of the face)
  double marker_size = 0.06;
  FixedFrame hand_camera;  // TCP -> hand camera optical frame
  FixedFrame ft_sensor;    // arm last link -> force-torque sensor
  FixedFrame left_camera;  // head last link -> left optical frame
  std::string right_camera_frame = "stereo_right_optical_frame";
  double stereo_baseline = 0.12;  // right camera sits at +baseline along the left optical x
  int image_width = 1024, image_height = 768;
  std::string left_camera_info, right_camera_info;  // absolute paths (may not exist)
  // A mono camera on the head beside the stereo pair (e.g. an RGB camera; frame "" when none):
  // head last link -> its optical frame, and its camera_info file (absolute path).
  FixedFrame mono_camera;
  std::string mono_camera_info;
  // The camera a calibration measures the arm's target with (key `head.calibration_camera`):
  // "stereo" (the pair) or "mono" (head.mono_camera alone; the pixel-level fit needs no stereo).
  std::string calibration_camera = "stereo";
  // Head poses are empty for a head without joints (cameras on a stand, eye-to-hand).
  std::vector<double> arm_calibration_pose, arm_home, head_calibration_pose, head_home;
  // The robot's ROS interfaces the calibration uses (keys arm.controller, head.controller: their
  // control_msgs/FollowJointTrajectory actions; head.stereo_camera.namespace: NS of the stereo
  // pair's NS/{left,right}/{image_raw,camera_info}; head.mono_camera.namespace: NS of the mono
  // camera's NS/{image_raw,camera_info}); "" when the description does not name them
  // (then the calibration nets' own names hold). Valid ROS graph names, checked at load.
  std::string arm_controller, head_controller, stereo_namespace, mono_namespace;
  // What a calibration estimates (key `free_params`, as Fetch's robot_calibration names them;
  // freeParams below); empty: everything it can.
  std::vector<std::string> free_params;
};

// The parameters a calibration from the arm's target seen by the head's camera estimates:
// `fixed_point` (the head's mount: base -> head link 0), `target_offset` (TCP -> target) and the
// zero offsets of the joints listed (indices into arm / head). Only the offsets of arm joints
// 2..n-1 and of the head joints after the first can be estimated: the others are
// indistinguishable from a turn of the head mount (arm joint 1, the pan) or of the target offset
// (the arm's last joint). The rest is held at its nominal value.
struct FreeParams {
  bool fixed_point = true, target_offset = true;
  std::vector<size_t> arm, head;
};
// From the description's free_params: names `fixed_point`, `target_offset`, `joint_offsets` (all
// that can be estimated) and single joints by name; empty: all. Throws std::runtime_error naming
// the description's file, the key and the unknown or inestimable name (with the known ones).
FreeParams freeParams(const RobotDescription& description);

// The description with `camera` ("stereo" or "mono") as its calibration camera; throws
// std::runtime_error naming `where` (a file and key, a parameter) and the value when it is neither,
// or "mono" on a head without a mono camera.
RobotDescription withCalibrationCamera(RobotDescription description, const std::string& camera, const std::string& where);

// Loads the description; throws std::runtime_error naming the file and the key on bad input.
RobotDescription loadRobotDescription(const std::string& path);
// The example robot shipped with this package (config/example/robot.yaml: a 7-joint arm, a
// pan-tilt stereo head), found with ros::package::getPath; for tests and docs.
std::string exampleRobotDescriptionPath();

// Forward kinematics of a description. Joint vectors: one angle per chain joint (a head without
// joints: empty).
class RobotModel {
 public:
  explicit RobotModel(RobotDescription description) : d_(std::move(description)) {}
  const RobotDescription& description() const { return d_; }

  Eigen::Isometry3d tcp(const std::vector<double>& arm_q) const;          // base -> TCP
  Eigen::Isometry3d marker(const std::vector<double>& arm_q) const;       // base -> marker
  Eigen::Isometry3d handCamera(const std::vector<double>& arm_q) const;   // base -> hand optical
  Eigen::Isometry3d ftSensor(const std::vector<double>& arm_q) const;     // base -> F/T sensor
  Eigen::Isometry3d headBase() const { return d_.head.mount; }            // base -> head_link_0
  Eigen::Isometry3d leftCamera(const std::vector<double>& head_q) const;  // base -> left optical
  Eigen::Isometry3d rightCamera(const std::vector<double>& head_q) const; // base -> right optical
  Eigen::Isometry3d monoCamera(const std::vector<double>& head_q) const;  // base -> mono optical
  // base -> the optical frame of the calibration camera: the left one of the pair, or the mono one.
  Eigen::Isometry3d calibrationCamera(const std::vector<double>& head_q) const;
  // Right optical frame in the left optical frame (pure translation by the baseline).
  Eigen::Isometry3d leftToRight() const;

  // Pan and tilt (rad) that put `target` (base frame) on the optical axis of the camera centred
  // between the two stereo cameras ("look at the TCP", paper Fig. 3.1). Iterative, from the
  // given start; clamps to the joint limits. Throws std::logic_error for a head without joints.
  std::array<double, 2> lookAt(const Eigen::Vector3d& target, std::array<double, 2> start = {0, 0}) const;

 private:
  RobotDescription d_;
};

}  // namespace robot_description
