#include <cmath>

#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/block_harness.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;

TEST(CreateRobotConfiguration, AnglesInDegreesBecomeRadiansWithJointNames) {
  BlockHarness h("imagenets/CreateRobotConfiguration");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("angles", std::vector<double>{10, 20, 30, 40, 50, 60, 70}).run();
  const auto js = h.output<sensor_msgs::JointState>("configuration");
  ASSERT_TRUE(js);
  ASSERT_EQ(js->name.size(), 7u);
  EXPECT_EQ(js->name[0], "arm_joint_1");
  EXPECT_NEAR(js->position[6], 70 * M_PI / 180, 1e-12);
}

TEST(CreateRobotConfiguration, HeadGroupHasPanAndTilt) {
  BlockHarness h("imagenets/CreateRobotConfiguration");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("group", std::string("head")).set("angles", std::vector<double>{-10, 30}).run();
  EXPECT_EQ(h.output<sensor_msgs::JointState>("configuration")->name,
            (std::vector<std::string>{"head_pan_joint", "head_tilt_joint"}));
}

TEST(CreateRobotConfiguration, OutOfLimitOrWrongCountIsAClearError) {
  BlockHarness h("imagenets/CreateRobotConfiguration");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("angles", std::vector<double>{0, 0, 0, 150, 0, 0, 0});
  const std::string error = h.runError();
  EXPECT_NE(error.find("property 'angles'"), std::string::npos) << error;
  EXPECT_NE(error.find("arm_joint_4"), std::string::npos) << error;
  EXPECT_NE(h.set("angles", std::vector<double>{0, 0}).runError(), "");
  EXPECT_EQ(h.stats().failures, 2u);
}
