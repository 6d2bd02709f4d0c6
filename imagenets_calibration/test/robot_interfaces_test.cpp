// The robot's controllers and camera topics from its calibration config, set on the shipped
// calibration nets (the live one and the bag one): every block holding the usual name gets the
// robot's, sub-nets included; what the config does not name stays.
#include "imagenets_calibration/robot_interfaces.h"

#include <gtest/gtest.h>

#include <sstream>

#include "imagenets/executor.h"
#include "imagenets/inner_net.h"
#include "imagenets/net.h"
#include "imagenets/package_file.h"
#include "robot_description/robot_model.h"

namespace imagenets_calibration {
namespace {

std::unique_ptr<imagenets::Executor> shippedNet(const std::string& sample_net) {
  imagenets::NetSpec spec =
      imagenets::parseNetFile(imagenets::packageFile("imagenets_calibration", "config/nets/calibration.yaml"));
  spec.block("samples").setProperty("net", imagenets::packageFile("imagenets_calibration", "config/nets/" + sample_net));
  return std::make_unique<imagenets::Executor>(imagenets::Net::build(spec));
}

// A property of block `block` of the sub-net at `path` ("samples/motion": the sample net's motion
// sub-net; "" for the top net's).
std::string property(const imagenets::Executor& exec, const std::string& path, const std::string& block,
                     const std::string& name) {
  const imagenets::Executor* net = &exec;
  std::stringstream subs(path);
  for (std::string sub; std::getline(subs, sub, '/');) {
    const auto& node = net->net().node(net->net().findNode(sub));
    net = dynamic_cast<const imagenets::InnerNet&>(*node.block).innerExecutor();
  }
  const int i = net->net().findNode(block);
  EXPECT_GE(i, 0) << block;
  return i < 0 ? "" : imagenets::toString(net->net().node(i).block->propertyValue(name));
}

robot_description::RobotDescription myRobot() {
  robot_description::RobotDescription d;
  d.source = "my_robot/calibration.yaml";
  d.arm_controller = "arm_with_torso_controller/follow_joint_trajectory";
  d.head_controller = "/robot/head_controller/follow_joint_trajectory";
  d.stereo_namespace = "head_camera/stereo";
  return d;
}

TEST(RobotInterfaces, TheLiveNetMovesThroughTheRobotsControllersAndReadsItsCameras) {
  auto exec = shippedNet("calibration_sample.yaml");
  EXPECT_EQ(property(*exec, "samples/motion", "move_arm", "action"), "arm_controller/follow_joint_trajectory");
  const auto lines = applyRobotInterfaces(myRobot(), *exec);
  EXPECT_EQ(lines, (std::vector<std::string>{
                       "arm.controller 'arm_with_torso_controller/follow_joint_trajectory': samples/motion/move_arm_approach, "
                       "samples/motion/move_arm",
                       "head.controller '/robot/head_controller/follow_joint_trajectory': samples/motion/move_head",
                       // the plan block reads a bag when told to: its topics too
                       "head.stereo_camera.namespace 'head_camera/stereo': samples/grab, plan"}));
  EXPECT_EQ(property(*exec, "samples/motion", "move_arm_approach", "action"), "arm_with_torso_controller/follow_joint_trajectory");
  EXPECT_EQ(property(*exec, "samples/motion", "move_arm", "action"), "arm_with_torso_controller/follow_joint_trajectory");
  EXPECT_EQ(property(*exec, "samples/motion", "move_head", "action"), "/robot/head_controller/follow_joint_trajectory");
  EXPECT_EQ(property(*exec, "samples", "grab", "camera"), "head_camera/stereo");
  EXPECT_EQ(property(*exec, "", "plan", "bag_camera"), "head_camera/stereo");
  // The blocks' other settings stay.
  EXPECT_EQ(property(*exec, "samples/motion", "move_head", "max_velocity"), "0.9");
}

TEST(RobotInterfaces, WhatTheConfigDoesNotNameKeepsTheNetsNames) {
  auto exec = shippedNet("calibration_sample.yaml");
  robot_description::RobotDescription d = myRobot();
  d.arm_controller = d.stereo_namespace = "";
  EXPECT_EQ(applyRobotInterfaces(d, *exec).size(), 1u);
  EXPECT_EQ(property(*exec, "samples/motion", "move_arm", "action"), "arm_controller/follow_joint_trajectory");
  EXPECT_EQ(property(*exec, "samples/motion", "move_head", "action"), "/robot/head_controller/follow_joint_trajectory");
  EXPECT_EQ(property(*exec, "samples", "grab", "camera"), "stereo");
  EXPECT_TRUE(applyRobotInterfaces(robot_description::RobotDescription{}, *exec).empty());
}

// The one-camera sample net reads the mono camera the config names; the stereo name has no block.
TEST(RobotInterfaces, TheMonoNetReadsTheRobotsMonoCamera) {
  auto exec = shippedNet("calibration_sample_mono.yaml");
  robot_description::RobotDescription d = myRobot();
  d.mono_namespace = "rgb_camera";
  const auto lines = applyRobotInterfaces(d, *exec);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[3], "head.mono_camera.namespace 'rgb_camera': samples/grab");
  EXPECT_EQ(property(*exec, "samples", "grab", "camera"), "rgb_camera");
  EXPECT_EQ(property(*exec, "samples/motion", "move_arm", "action"), "arm_with_torso_controller/follow_joint_trajectory");
}

// Offline the bag's samples are found under the robot's camera topics; the bag net moves nothing.
TEST(RobotInterfaces, TheBagNetReadsTheRobotsCameraTopics) {
  auto exec = shippedNet("calibration_sample_bag.yaml");
  const auto lines = applyRobotInterfaces(myRobot(), *exec);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_NE(lines[0].find("arm.controller 'arm_with_torso_controller/follow_joint_trajectory': no block of "),
            std::string::npos)
      << lines[0];
  EXPECT_EQ(lines[2], "head.stereo_camera.namespace 'head_camera/stereo': plan, samples/bag");
  EXPECT_EQ(property(*exec, "", "plan", "bag_camera"), "head_camera/stereo");
  EXPECT_EQ(property(*exec, "samples", "bag", "bag_camera"), "head_camera/stereo");
}

}  // namespace
}  // namespace imagenets_calibration
