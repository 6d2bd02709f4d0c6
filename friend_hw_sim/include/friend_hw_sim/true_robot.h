// The simulator's hidden deviation of the true robot from the nominal description: the robot the
// simulator runs (and renders) differs from robot.yaml by this error, which the calibration has
// to find. Only the simulator and tests read it.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "robot_description/robot_model.h"

namespace YAML {
class Node;
}

namespace friend_hw_sim {

struct TrueRobotError {
  Eigen::Vector3d head_mount_xyz = Eigen::Vector3d::Zero();  // m, added to the head mount
  Eigen::Vector3d head_mount_rpy = Eigen::Vector3d::Zero();  // rad, rotation applied after the mount
  Eigen::Vector3d marker_xyz = Eigen::Vector3d::Zero();
  Eigen::Vector3d marker_rpy = Eigen::Vector3d::Zero();
  std::vector<double> arm_joint_offsets, head_joint_offsets;  // rad, added to the joints' offsets
};

// Reads `true_error` settings (see config/friend/true_error.yaml) for the robot `nominal`. With
// `seed` > 0 the error is drawn at random with the given magnitudes (repeatable per seed), one
// zero offset per joint of `nominal`'s arm and head; with seed 0 the explicit values are used.
// `magnitude` scales the `random` magnitudes (a study over robots K times as far off as the file's;
// ignored for explicit values). Throws naming the key (or the magnitude) on bad input.
TrueRobotError trueErrorFromYaml(const YAML::Node& node, const std::string& where,
                                 const robot_description::RobotDescription& nominal, int seed_override = -1,
                                 double magnitude = 1.0);
TrueRobotError loadTrueError(const std::string& path, const robot_description::RobotDescription& nominal,
                             int seed_override = -1, double magnitude = 1.0);
// The description of the true robot.
robot_description::RobotDescription applyTrueError(const robot_description::RobotDescription& nominal,
                                                   const TrueRobotError& error);

// What a calibration of the head's fixed point (base -> head link 0) from the arm's marker can find
// at best, for comparing with it. Effective: the true mount with the pan encoder's zero offset
// folded in (it turns the whole head about the mount's z). Identifiable: the effective mount with
// arm joint 1's zero offset folded in as well (it turns the whole arm about joint 1's axis, which
// the images cannot tell from the head mount turning the other way about that axis).
Eigen::Isometry3d effectiveHeadBase(const robot_description::RobotDescription& nominal, const TrueRobotError& error);
Eigen::Isometry3d identifiableHeadBase(const robot_description::RobotDescription& nominal, const TrueRobotError& error);

}  // namespace friend_hw_sim
