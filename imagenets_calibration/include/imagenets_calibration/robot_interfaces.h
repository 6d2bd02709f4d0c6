// The robot's ROS interfaces named in its calibration config (robot_description: arm.controller,
// head.controller, head.stereo_camera.namespace) set on a calibration net tree. The calibration
// nets are written with the names ros_control robots usually have (arm_controller/
// follow_joint_trajectory, head_controller/follow_joint_trajectory, the stereo pair under
// `stereo`); every block holding one of them gets the robot's name instead. Used by the
// calibration node and the offline calibration from a bag: one place knows which block property
// carries which interface.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace imagenets {
class Executor;
}
namespace robot_description {
struct RobotDescription;
}

namespace imagenets_calibration {

// One interface of the config: where the nets hold the usual name it replaces.
struct RobotInterface {
  std::string key;    // the config's key, "arm.controller"
  std::string value;  // the robot's name; "" when the config names none
  std::string usual;  // the name the nets are written with
  std::vector<std::pair<std::string, std::string>> properties;  // (block type, property) holding it
  bool action = false;  // a FollowJointTrajectory action server (missingControllers)
};

// The interfaces a calibration config can name, with the config's values.
std::vector<RobotInterface> robotInterfaces(const robot_description::RobotDescription& config);

// Sets the config's interfaces on `net` and its sub-nets; interfaces the config does not name keep
// the nets' names. Returns one line per interface set, "arm.controller
// 'my_arm/follow_joint_trajectory': samples/move_arm_approach, samples/move_arm" (no blocks: the
// net does not use it, e.g. the bag net's motion). Throws std::runtime_error naming the config
// file and the key when a block refuses the value.
std::vector<std::string> applyRobotInterfaces(const robot_description::RobotDescription& config, imagenets::Executor& net);

// The config's FollowJointTrajectory actions (key, resolved name) that no server offers on the
// master within `timeout` seconds (checked together): "arm.controller '/my_arm/follow_joint_
// trajectory' (calibration.yaml): no action server after 10.0 s (the master knows the
// FollowJointTrajectory servers /arm_controller/follow_joint_trajectory)". Empty: all there.
std::vector<std::string> missingControllers(const robot_description::RobotDescription& config, double timeout);

}  // namespace imagenets_calibration
