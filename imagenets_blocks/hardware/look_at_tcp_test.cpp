#include <cmath>

#include <boost/make_shared.hpp>
#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/block_harness.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;

TEST(LookAtTcp, CentresTheTcpOnTheStereoAxisOfTheNominalRobot) {
  BlockHarness h("imagenets/LookAtTcp");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  const auto d = robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath());
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  arm->position = {-0.5, 1.0, 1.2, 1.3, -0.3, 1.2, 0.0};
  h.input("arm_configuration", arm).run();
  const auto head = h.output<sensor_msgs::JointState>("head_configuration");
  ASSERT_TRUE(head);
  ASSERT_EQ(head->position.size(), 2u);
  const robot_description::RobotModel model(d);
  Eigen::Isometry3d centre = model.leftCamera(head->position);
  centre.translate(Eigen::Vector3d(d.stereo_baseline / 2, 0, 0));
  const Eigen::Vector3d p = centre.inverse() * model.tcp(arm->position).translation();
  EXPECT_GT(p.z(), 0.2);
  EXPECT_LT(std::hypot(p.x(), p.y()), 1e-6 * p.z());
}

TEST(LookAtTcp, MissingArmJointIsNamed) {
  BlockHarness h("imagenets/LookAtTcp");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = {"arm_joint_1"};
  arm->position = {0.0};
  const std::string error = h.input("arm_configuration", arm).runError();
  EXPECT_NE(error.find("arm_joint_2"), std::string::npos) << error;
  EXPECT_NE(error.find("arm_configuration"), std::string::npos) << error;
  // A required input without a value: the one invocation path names it, the block never runs.
  EXPECT_EQ(h.clear("arm_configuration").runError(), "input 'arm_configuration' has no value");
}
