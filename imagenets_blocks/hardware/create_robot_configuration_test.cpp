#include <cmath>

#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/registry.h"

using namespace imagenets;

namespace {
// Runs a block once on the given inputs (by port order) and returns its outputs.
std::vector<Value> runOnce(Block& block, std::vector<Value> inputs = {}) {
  inputs.resize(block.inputs().size());
  Context ctx("under_test", block.inputs(), block.outputs(), inputs, block.propertyValues());
  block.process(ctx);
  return ctx.outputs();
}
}  // namespace

TEST(CreateRobotConfiguration, AnglesInDegreesBecomeRadiansWithJointNames) {
  auto block = BlockRegistry::instance().create("imagenets/CreateRobotConfiguration");
  block->setProperty("angles", std::vector<double>{10, 20, 30, 40, 50, 60, 70});
  const auto out = runOnce(*block);
  const auto js = out[block->outputIndex("configuration")].as<sensor_msgs::JointState>();
  ASSERT_TRUE(js);
  ASSERT_EQ(js->name.size(), 7u);
  EXPECT_EQ(js->name[0], "arm_joint_1");
  EXPECT_NEAR(js->position[6], 70 * M_PI / 180, 1e-12);
}

TEST(CreateRobotConfiguration, HeadGroupHasPanAndTilt) {
  auto block = BlockRegistry::instance().create("imagenets/CreateRobotConfiguration");
  block->setProperty("group", std::string("head"));
  block->setProperty("angles", std::vector<double>{-10, 30});
  const auto js = runOnce(*block)[0].as<sensor_msgs::JointState>();
  EXPECT_EQ(js->name, (std::vector<std::string>{"head_pan_joint", "head_tilt_joint"}));
}

TEST(CreateRobotConfiguration, OutOfLimitOrWrongCountIsAClearError) {
  auto block = BlockRegistry::instance().create("imagenets/CreateRobotConfiguration");
  block->setProperty("angles", std::vector<double>{0, 0, 0, 150, 0, 0, 0});
  try {
    runOnce(*block);
    FAIL() << "expected an error";
  } catch (const BlockError& e) {
    EXPECT_NE(std::string(e.what()).find("property 'angles'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("arm_joint_4"), std::string::npos) << e.what();
  }
  block->setProperty("angles", std::vector<double>{0, 0});
  EXPECT_THROW(runOnce(*block), BlockError);
}
