#include <cmath>

#include <boost/make_shared.hpp>
#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include "robot_description/robot_model.h"
#include "imagenets/registry.h"

using namespace imagenets;

TEST(LookAtTcp, CentresTheTcpOnTheStereoAxisOfTheNominalRobot) {
  auto block = BlockRegistry::instance().create("imagenets/LookAtTcp");
  const auto d = robot_description::loadRobotDescription("config/friend/robot.yaml");
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = d.arm.names();
  arm->position = {-0.5, 1.0, 1.2, 1.3, -0.3, 1.2, 0.0};
  std::vector<Value> inputs{PortType::of<sensor_msgs::JointState>().wrap(boost::shared_ptr<const sensor_msgs::JointState>(arm))};
  Context ctx("look", block->inputs(), block->outputs(), inputs, block->propertyValues());
  block->process(ctx);
  const auto head = ctx.outputs()[block->outputIndex("head_configuration")].as<sensor_msgs::JointState>();
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
  auto block = BlockRegistry::instance().create("imagenets/LookAtTcp");
  auto arm = boost::make_shared<sensor_msgs::JointState>();
  arm->name = {"arm_joint_1"};
  arm->position = {0.0};
  std::vector<Value> inputs{PortType::of<sensor_msgs::JointState>().wrap(boost::shared_ptr<const sensor_msgs::JointState>(arm))};
  Context ctx("look", block->inputs(), block->outputs(), inputs, block->propertyValues());
  try {
    block->process(ctx);
    FAIL() << "expected an error";
  } catch (const BlockError& e) {
    EXPECT_NE(std::string(e.what()).find("arm_joint_2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("arm_configuration"), std::string::npos) << e.what();
  }
}
