#include "imagenets_calibration/robot_interfaces.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <ros/master.h>
#include <ros/names.h>
#include <ros/ros.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/net_wide_property.h"
#include "robot_description/robot_model.h"

namespace imagenets_calibration {

std::vector<RobotInterface> robotInterfaces(const robot_description::RobotDescription& c) {
  const std::pair<std::string, std::string> motion{"imagenets/FollowJointTrajectory", "action"};
  return {
      {"arm.controller", c.arm_controller, "arm_controller/follow_joint_trajectory", {motion}, true},
      {"head.controller", c.head_controller, "head_controller/follow_joint_trajectory", {motion}, true},
      // Live the grab reads the pair; offline the bag's samples are found under the same topics.
      {"head.stereo_camera.namespace",
       c.stereo_namespace,
       "stereo",
       {{"imagenets/GrabStereoPair", "camera"},
        {"imagenets/CalibrationPlan", "bag_camera"},
        {"imagenets/BagCalibrationSample", "bag_camera"}}},
      {"head.mono_camera.namespace", c.mono_namespace, "head_camera", {{"imagenets/GrabImage", "camera"}}},
  };
}

std::vector<std::string> applyRobotInterfaces(const robot_description::RobotDescription& config, imagenets::Executor& net) {
  std::vector<std::string> lines;
  for (const RobotInterface& i : robotInterfaces(config)) {
    if (i.value.empty()) continue;
    std::string blocks;
    for (const auto& [type, property] : i.properties) {
      try {
        for (const std::string& b : imagenets::replacePropertyValueInNetTree(net, type, property, i.usual, i.value)) {
          blocks += (blocks.empty() ? "" : ", ") + b;
        }
      } catch (const std::exception& e) {
        throw std::runtime_error(config.source + ": " + i.key + ": '" + i.value + "' cannot be set on the net: " + e.what());
      }
    }
    lines.push_back(i.key + " '" + i.value + "': " + (blocks.empty() ? "no block of " + net.net().origin() + " uses it" : blocks));
  }
  return lines;
}

std::vector<std::string> missingControllers(const robot_description::RobotDescription& config, double timeout) {
  // A FollowJointTrajectory server publishes ACTION/result of this type (actionlib's topics).
  const std::string result_type = "control_msgs/FollowJointTrajectoryActionResult";
  std::vector<std::pair<std::string, std::string>> wanted;  // key, resolved action
  for (const RobotInterface& i : robotInterfaces(config)) {
    if (i.value.empty() || !i.action) continue;
    wanted.emplace_back(i.key, ros::names::resolve(i.value));
  }
  std::vector<std::string> known, missing;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  do {
    ros::master::V_TopicInfo topics;
    if (!ros::master::getTopics(topics)) topics.clear();
    known.clear();
    for (const auto& t : topics) {
      if (t.datatype == result_type) known.push_back(t.name.substr(0, t.name.size() - std::string("/result").size()));
    }
    missing.clear();
    for (const auto& w : wanted) {
      if (std::find(known.begin(), known.end(), w.second) == known.end()) missing.push_back(w.first + " '" + w.second + "'");
    }
    if (missing.empty()) return {};
    ros::WallDuration(0.2).sleep();
  } while (ros::WallTime::now() < deadline && ros::ok());
  std::string servers;
  for (const auto& k : known) servers += (servers.empty() ? "" : ", ") + k;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f", timeout);
  for (std::string& m : missing) {
    m += " (" + config.source + "): no action server after " + seconds + " s (" +
         (servers.empty() ? std::string("the master knows no FollowJointTrajectory server")
                          : "the master knows the FollowJointTrajectory servers " + servers) +
         ")";
  }
  return missing;
}

}  // namespace imagenets_calibration
