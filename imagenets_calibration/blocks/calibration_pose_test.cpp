#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <std_msgs/Int32.h>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/block_harness.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;

namespace {
boost::shared_ptr<const imagenets_calibration_msgs::CalibrationPlan> paperPlan() {
  BlockHarness h("imagenets/CalibrationPlan");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("method", std::string("paper")).set("loops", 3);
  h.run();
  return h.output<imagenets_calibration_msgs::CalibrationPlan>("plan");
}
}  // namespace

TEST(CalibrationPose, PoseKFromTheRepetitionOrTheIndexProperty) {
  const auto plan = paperPlan();
  BlockHarness target("imagenets/CalibrationPose");
  auto k = boost::make_shared<std_msgs::Int32>();
  k->data = 2;
  target.input("plan", plan).input("repetition", k);
  target.run();
  EXPECT_EQ(target.output<sensor_msgs::JointState>("arm")->position, plan->arm[2].position);
  EXPECT_EQ(target.output<sensor_msgs::JointState>("head")->position, plan->head[2].position);
  BlockHarness approach("imagenets/CalibrationPose");
  approach.set("stage", std::string("approach")).set("index", 1).input("plan", plan);
  approach.run();
  EXPECT_EQ(approach.output<sensor_msgs::JointState>("arm")->position, plan->arm_approach[1].position);
  EXPECT_NE(approach.output<sensor_msgs::JointState>("arm")->position, plan->arm[1].position);
}

TEST(CalibrationPose, AnIndexBeyondThePlanIsANamedError) {
  BlockHarness h("imagenets/CalibrationPose");
  h.set("index", 3).input("plan", paperPlan());
  EXPECT_NE(h.runError().find("property 'index': sample 3 of a plan of 3 samples"), std::string::npos);
}
