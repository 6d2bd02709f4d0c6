#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationSample.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>

#include "imagenets_calibration/calibration.h"
#include "imagenets/blocks/block_harness.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;

TEST(AssembleCalibrationSample, JointsInTheDescriptionsOrderAndBothObservations) {
  const auto d = robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath());
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  std::reverse(arm->name.begin(), arm->name.end());  // a driver's order
  arm->position = {7, 6, 5, 4, 3, 2, 1};
  auto head = boost::make_shared<sensor_msgs::JointState>();
  head->name = d.head.names();
  head->position = {0.1, 0.2};
  auto left = boost::make_shared<imagenets_calibration_msgs::MarkerObservation>();
  left->found = true;
  left->threshold = 90;
  auto right = boost::make_shared<imagenets_calibration_msgs::MarkerObservation>();
  right->reason = "glare";
  auto image = boost::make_shared<sensor_msgs::Image>();
  image->header.stamp = ros::Time(12.5);
  BlockHarness h("imagenets/AssembleCalibrationSample");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.input("arm_joints", arm).input("head_joints", head).input("left", left).input("right", right).input("image", image);
  h.run();
  const auto s = h.output<imagenets_calibration_msgs::CalibrationSample>("sample");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->arm_q, (std::vector<double>{1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(s->head_q, (std::vector<double>{0.1, 0.2}));
  EXPECT_EQ(s->left.threshold, 90);
  EXPECT_EQ(s->right.reason, "glare");
  EXPECT_EQ(s->stamp, 12.5);
  EXPECT_FALSE(s->valid);  // raw: the solve decides
  arm->name.pop_back();
  arm->position.pop_back();
  EXPECT_NE(h.input("arm_joints", arm).runError().find("input 'arm_joints'"), std::string::npos);
}

TEST(AssembleCalibrationSample, OneCamerasObservationAlone) {
  const auto d = robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath());
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  arm->position = {1, 2, 3, 4, 5, 6, 7};
  auto head = boost::make_shared<sensor_msgs::JointState>();
  head->name = d.head.names();
  head->position = {0.1, 0.2};
  auto mono = boost::make_shared<imagenets_calibration_msgs::MarkerObservation>();
  mono->found = true;
  mono->reprojection_error = 0.02;
  auto image = boost::make_shared<sensor_msgs::Image>();
  image->header.stamp = ros::Time(3.25);
  BlockHarness h("imagenets/AssembleCalibrationSample");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.input("arm_joints", arm).input("head_joints", head).input("image", image);
  // Without any camera's observation there is no sample.
  EXPECT_NE(h.runError().find("inputs 'left', 'right', 'mono': none has an observation"), std::string::npos);
  h.input("mono", mono);
  h.run();
  const auto s = h.output<imagenets_calibration_msgs::CalibrationSample>("sample");
  ASSERT_TRUE(s);
  EXPECT_TRUE(s->mono.found);
  EXPECT_EQ(s->mono.reprojection_error, 0.02);
  EXPECT_FALSE(s->left.found);
  EXPECT_FALSE(s->right.found);
  EXPECT_EQ(s->stamp, 3.25);
}
