// Joint positions by name from a sensor_msgs/JointState, the way every driver publishes them
// (any order, other joints mixed in). The one reader that blocks, simulator and calibration use.
#pragma once

#include <string>
#include <vector>

#include <sensor_msgs/JointState.h>

namespace robot_description {

// Positions of `names`, in that order. Throws std::invalid_argument naming the missing joint, or
// saying that the message has fewer positions than names.
std::vector<double> jointPositions(const sensor_msgs::JointState& state, const std::vector<std::string>& names);

}  // namespace robot_description
