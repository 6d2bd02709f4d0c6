#include <gtest/gtest.h>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/JointState.h>

#include "imagenets_calibration/calibration.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/package_file.h"
#include "imagenets/vision/frames.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;
using namespace imagenets_calibration;

TEST(PredictMarkerPose, TheNominalModelsMarkerInBothCameras) {
  const RobotModel model(robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath()));
  const auto& d = model.description();
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  arm->position = d.arm_calibration_pose;
  auto head = boost::make_shared<sensor_msgs::JointState>();
  head->name = {d.head.names()[1], d.head.names()[0]};  // by name, in any order
  head->position = {d.head_calibration_pose[1], d.head_calibration_pose[0]};
  BlockHarness h("imagenets/PredictMarkerPose");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.input("arm_joints", arm).input("head_joints", head);
  h.run();
  const Eigen::Isometry3d left = imagenets::frames::toIsometry(h.output<geometry_msgs::PoseStamped>("left")->pose, "left");
  const Eigen::Isometry3d right = imagenets::frames::toIsometry(h.output<geometry_msgs::PoseStamped>("right")->pose, "right");
  const Eigen::Isometry3d expected = model.leftCamera(d.head_calibration_pose).inverse() * model.marker(d.arm_calibration_pose);
  EXPECT_LT((left.translation() - expected.translation()).norm(), 1e-9);
  EXPECT_GT(left.translation().z(), 0.2);  // in front of the camera
  EXPECT_LT(((model.leftToRight() * right).translation() - left.translation()).norm(), 1e-9);
  EXPECT_FALSE(h.hasOutput("mono"));  // this head has no mono camera
  head->name = {"pan"};
  head->position = {0};
  EXPECT_NE(h.input("head_joints", head).runError().find("input 'head_joints'"), std::string::npos);
}

TEST(PredictMarkerPose, TheMonoCamerasToo) {
  const std::string path = imagenets::packageFile("robot_description", "config/mobile_manipulator/robot.yaml");
  const RobotModel model(robot_description::loadRobotDescription(path));
  const auto& d = model.description();
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  arm->position = d.arm_calibration_pose;
  auto head = boost::make_shared<sensor_msgs::JointState>();
  head->name = d.head.names();
  head->position = d.head_calibration_pose;
  BlockHarness h("imagenets/PredictMarkerPose");
  h.set("description", path);
  h.input("arm_joints", arm).input("head_joints", head);
  h.run();
  const auto mono = h.output<geometry_msgs::PoseStamped>("mono");
  ASSERT_TRUE(mono);
  EXPECT_EQ(mono->header.frame_id, "head_camera_rgb_optical_frame");
  const Eigen::Isometry3d expected = model.monoCamera(d.head_calibration_pose).inverse() * model.marker(d.arm_calibration_pose);
  EXPECT_LT((imagenets::frames::toIsometry(mono->pose, "mono").translation() - expected.translation()).norm(), 1e-9);
}
