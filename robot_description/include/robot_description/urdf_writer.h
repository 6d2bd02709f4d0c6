// The URDF of a robot whose kinematics were changed from its description's (a calibration's
// result, the simulator's true robot), for robot_state_publisher. A description with its own URDF
// (`urdf:` in its YAML file, e.g. config/six_axis) gets that file back with the changes written
// into the joints' origins: every link and joint keeps its name, everything else stays as written.
// A description of DH tables gets the URDF generated from the changed description (urdf_generator.h).
#pragma once

#include <string>

#include "robot_description/robot_model.h"

namespace robot_description {

// The URDF file a description's kinematics were read from (its YAML's `urdf` key, resolved
// against the YAML file), or "" for a description of DH tables.
std::string urdfFileOf(const RobotDescription& description);

struct UrdfJoint {
  std::string name, parent, child;  // the joint and its parent and child links
};
// The fixed joint that places a chain's link 0 (for the head: the fixed point; a chain without
// joints, a camera on a stand: the fixed joint to its tip link) in the URDF that
// writeUrdf writes, and the fixed joint whose child is link `link` (e.g. the marker's frame).
// Throws naming the URDF and the link when there is none.
UrdfJoint urdfChainMountJoint(const RobotDescription& description, const KinematicChain& chain);
UrdfJoint urdfFixedJoint(const RobotDescription& description, const std::string& link);

// The URDF of `changed`, a description derived from `nominal` (same chains and frames, other
// values). For a description with its own URDF: that file with, for every difference, the origin
// of one joint rewritten: a chain joint's zero offset is folded into its origin (URDF origin *
// the joint's motion by the offset; robot_state_publisher ignores <calibration>), a chain's mount
// goes into the fixed joint that places its link 0, a fixed frame (tool, marker, hand camera,
// force-torque sensor, left camera) into the fixed joint whose child it is; `note` becomes a
// comment at the top; the robot keeps its name. Otherwise generateUrdf(changed, robot_name, note).
// Throws naming the file and the joint or link when the URDF cannot hold a change.
std::string writeUrdf(const RobotDescription& nominal, const RobotDescription& changed, const std::string& robot_name,
                      const std::string& note = "");

}  // namespace robot_description
