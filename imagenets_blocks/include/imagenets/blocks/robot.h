// Robot description helpers shared by blocks: the description named by a block's `description`
// property (loaded once per file), and joint positions by name from an input port, both with
// errors that name the property or the port.
#pragma once

#include <string>
#include <vector>

#include <sensor_msgs/JointState.h>

#include "robot_description/robot_model.h"

namespace imagenets {
namespace blocks {

// The robot description in `path` ("" = the shipped config/friend/robot.yaml), loaded on first
// use and kept. Throws BlockError naming the property 'description' and the file's problem.
const robot_description::RobotDescription& robotDescription(const std::string& path);

// Positions of `names` in `state`; throws BlockError naming the input port and the missing joint.
std::vector<double> jointPositions(const sensor_msgs::JointState& state, const std::vector<std::string>& names,
                                   const std::string& port);

}  // namespace blocks
}  // namespace imagenets
