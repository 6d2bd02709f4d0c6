// Kinematics read from a URDF, the robot description the ROS world uses, with KDL (Debian's
// liborocos-kdl and kdl_parser): the serial chain between two links becomes a KinematicChain of
// robot_model.h (the one representation every kinematics of the project computes with), a run of
// fixed joints a fixed transform. KDL and urdf headers stay in the .cpp: robot_model.h is included
// by the blocks and the calibration.
#pragma once

#include <memory>
#include <string>

#include "robot_description/robot_model.h"

namespace robot_description {

class UrdfKinematics {
 public:
  // Parses URDF text; `source` (a file, a parameter) names it in errors. Throws
  // std::runtime_error naming the source when it does not parse.
  UrdfKinematics(const std::string& urdf_xml, const std::string& source);
  static UrdfKinematics fromFile(const std::string& path);
  UrdfKinematics(UrdfKinematics&&) noexcept;
  ~UrdfKinematics();

  const std::string& source() const;
  std::string rootLink() const;
  // The serial chain from link `root` to link `tip`: the fixed joints before the first moving
  // joint are its mount (so the mount's child is the first moving joint's parent link), each
  // moving joint one ChainJoint (origin, axis, and as its tip the fixed joints up to the next
  // moving one), limits and velocity from the URDF (a continuous joint: unlimited); tip_link is
  // `tip`. Fixed joints only (a camera on a stand): no joints, root -> tip is the mount. Throws
  // naming the source and the links when there is no such chain.
  KinematicChain chain(const std::string& root, const std::string& tip) const;
  // root -> tip through fixed joints only; throws naming the moving joint between them.
  Eigen::Isometry3d fixedTransform(const std::string& root, const std::string& tip) const;

 private:
  struct Data;
  std::unique_ptr<Data> data_;
};

// The links of a URDF that a robot description needs.
struct UrdfLinks {
  std::string base;                           // the arm and the head hang from it
  std::string arm_tip, tool, marker, hand_camera, ft_sensor;  // arm chain end; fixed to it: TCP, ...
  std::string head_tip, left_camera, right_camera;            // head chain end; stereo optical frames
  std::string mono_camera;                                    // fixed to the head chain end ("": none)
};

// `description` with its kinematics taken from the URDF between `links`: base frame, arm and head
// chains, tool, marker, hand camera and force-torque sensor frames, left camera frame and the
// stereo baseline (the right optical frame must be the left one moved along its x). The rest
// (marker size, image size, camera infos, poses, chain link prefixes) is kept. Throws naming the
// source and the link or joint that does not fit.
RobotDescription withUrdfKinematics(RobotDescription description, const UrdfKinematics& urdf, const UrdfLinks& links);
// The link names in the URDF generateUrdf(description) writes.
UrdfLinks generatedUrdfLinks(const RobotDescription& description);

// Where loadRobotDescription (robot_model.h) finds the URDF of a description in the URDF form
// (links named: arm.tip_link, ...): the file of its key `urdf` (relative to the YAML); without
// that key (or with `urdf: robot_description`), the file given here, else the parameter
// `robot_description` of this ROS node, found as ROS tools find it (searched up from the node's
// namespace, after remapping: robot_description:=other_name). "" = the parameter again. For a
// program without a ROS master: the offline calibration's --urdf.
void useUrdfFile(const std::string& path);
// The robot's own URDF that `description` (the URDF form) was read from, by those rules, as text;
// `source` says where from (the file, "parameter /robot_description"). "" for a DH description.
std::string ownUrdf(const RobotDescription& description, std::string& source);

}  // namespace robot_description
