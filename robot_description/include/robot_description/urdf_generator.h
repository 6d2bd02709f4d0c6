// URDF of the FRIEND robot generated from its DH description (no xacro in Debian, and one source
// of truth): every DH frame is a link named like in the description (arm_link_0..7,
// head_link_0..2), plus tcp, gripper marker, cameras, force-torque sensor; simple shapes for rviz.
#pragma once

#include <string>

#include "robot_description/robot_model.h"

namespace robot_description {

// Joint i of a chain (ChainJoint) becomes a revolute (prismatic) joint from link i-1 to an
// intermediate "<joint>_rotor" link (origin: the joint's origin with its zero offset turned in,
// e.g. Rz(theta_offset) for a DH row; its axis), then a fixed joint (the joint's tip, e.g.
// Tz(d) Tx(a) Rx(alpha)) to link i, so TF of link i equals the chain's frame i exactly.
// `note`: lines put in a comment at the top (e.g. what a calibration changed); "--" is not allowed
// in an XML comment and is written as "- -".
// `robot_name`: "" = the description's name.
std::string generateUrdf(const RobotDescription& description, const std::string& robot_name = "",
                         const std::string& note = "");

}  // namespace robot_description
