#include "imagenets/blocks/robot.h"

#include <map>
#include <mutex>

#include "imagenets/block.h"
#include "robot_description/joint_state.h"

namespace imagenets {
namespace blocks {

const robot_description::RobotDescription& robotDescription(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, robot_description::RobotDescription> cache;
  if (path.empty()) throw BlockError("property 'description' is empty: set it to the robot's description YAML");
  const std::string& file = path;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(file);
  if (it == cache.end()) {
    try {
      it = cache.emplace(file, robot_description::loadRobotDescription(file)).first;
    } catch (const std::exception& e) {
      throw BlockError(std::string("property 'description': ") + e.what());
    }
  }
  return it->second;
}

std::vector<double> jointPositions(const sensor_msgs::JointState& state, const std::vector<std::string>& names,
                                   const std::string& port) {
  try {
    return robot_description::jointPositions(state, names);
  } catch (const std::invalid_argument& e) {
    throw BlockError("input '" + port + "': " + e.what());
  }
}

}  // namespace blocks
}  // namespace imagenets
