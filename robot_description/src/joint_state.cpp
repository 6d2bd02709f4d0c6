#include "robot_description/joint_state.h"

#include <algorithm>
#include <stdexcept>

namespace robot_description {

std::vector<double> jointPositions(const sensor_msgs::JointState& state, const std::vector<std::string>& names) {
  if (state.name.size() != state.position.size()) {
    throw std::invalid_argument(std::to_string(state.name.size()) + " joint names but " +
                                std::to_string(state.position.size()) + " positions");
  }
  std::vector<double> q;
  q.reserve(names.size());
  for (const auto& n : names) {
    const auto it = std::find(state.name.begin(), state.name.end(), n);
    if (it == state.name.end()) throw std::invalid_argument("joint '" + n + "' is missing");
    q.push_back(state.position[it - state.name.begin()]);
  }
  return q;
}

}  // namespace robot_description
