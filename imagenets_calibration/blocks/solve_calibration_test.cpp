#include <gtest/gtest.h>
#include <geometry_msgs/TransformStamped.h>
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>
#include <imagenets_calibration_msgs/CalibrationSamples.h>

#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/package_file.h"
#include "robot_description/robot_model.h"

using imagenets::blocks::BlockHarness;
using namespace imagenets_calibration;

namespace {

struct Case {
  RobotModel model{robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath())};
  Eigen::Isometry3d truth = model.headBase() * Eigen::Translation3d(0.004, -0.003, 0.002);
  // Exact samples at the plan's poses, one of them a spurious detection.
  std::vector<Sample> samples(const std::string& method, int n) {
    std::vector<Sample> out;
    for (const auto& p : calibrationPoses(model, n, method)) {
      Sample s;
      s.arm_q = p.arm;
      s.head_q = p.head;
      s.left.found = s.right.found = true;
      s.left.pose = (truth * headChain(model, p.head)).inverse() * model.marker(p.arm);
      s.right.pose = model.leftToRight().inverse() * s.left.pose;
      s.left.reprojection_error = s.right.reprojection_error = 0.02;
      out.push_back(s);
    }
    out[1].left.pose.translation().x() += 0.03;
    out[1].right.pose.translation().x() += 0.03;
    return out;
  }
};

boost::shared_ptr<imagenets_calibration_msgs::CalibrationSamples> toSamplesMsg(const std::vector<Sample>& samples) {
  auto msg = boost::make_shared<imagenets_calibration_msgs::CalibrationSamples>();
  for (const auto& s : samples) msg->samples.push_back(toMsg(s));
  return msg;
}

}  // namespace

TEST(SolveCalibration, IsTheLibrarysCalibrateForBothMethods) {
  Case c;
  for (const std::string method : {"paper", "joint"}) {
    const auto samples = c.samples(method, 5);
    auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
    plan->method = method;
    plan->samples = 5;
    BlockHarness h("imagenets/SolveCalibration");
    h.set("description", robot_description::exampleRobotDescriptionPath());
    h.input("samples", toSamplesMsg(samples)).input("plan", plan);
    h.run();
    const Result net = fromMsg(*h.output<imagenets_calibration_msgs::CalibrationResult>("result"));
    CombineOptions combine;
    combine.min_valid_samples = 3;
    const Result library = calibrate(c.model, samples, method, FusionLimits(), combine);
    ASSERT_TRUE(net.success) << net.message;
    EXPECT_LT((net.fixed_point.translation() - library.fixed_point.translation()).norm(), 1e-12) << method;
    EXPECT_LT((net.fixed_point.translation() - c.truth.translation()).norm(), 1e-6) << method;
    EXPECT_EQ(net.rejected, std::vector<int>{1}) << method;
    EXPECT_EQ(net.method, method);
    const auto frame = h.output<geometry_msgs::TransformStamped>("fixed_point");
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->child_frame_id, "pth_fixed_point");
    EXPECT_EQ(frame->header.frame_id, c.model.description().base_frame);
  }
}

TEST(SolveCalibration, AFailedCalibrationIsAResultWithoutAFixedPoint) {
  Case c;
  auto samples = c.samples("paper", 3);
  for (auto& s : samples) s.left.found = s.right.found = false;
  auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
  plan->method = "paper";
  BlockHarness h("imagenets/SolveCalibration");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.input("samples", toSamplesMsg(samples)).input("plan", plan);
  h.run();
  const auto result = h.output<imagenets_calibration_msgs::CalibrationResult>("result");
  EXPECT_FALSE(result->success);
  EXPECT_NE(result->message.find("marker not found"), std::string::npos) << result->message;
  EXPECT_FALSE(h.hasOutput("fixed_point"));
  plan->method = "best";
  EXPECT_NE(h.input("plan", plan).runError().find("unknown calibration method 'best'"), std::string::npos);
}

TEST(SolveCalibration, MeasuresWithTheMonoCameraWhenToldTo) {
  // The mobile manipulator's samples as its mono camera sees them (no stereo observation).
  const std::string path = imagenets::packageFile("robot_description", "config/mobile_manipulator/robot.yaml");
  const auto stereo = robot_description::loadRobotDescription(path);
  const RobotModel model(robot_description::withCalibrationCamera(stereo, "mono", "test"));
  const Eigen::Isometry3d truth = model.headBase() * Eigen::Translation3d(0.004, -0.003, 0.002);
  std::vector<Sample> samples;
  for (const auto& p : calibrationPoses(model, 5, "paper")) {
    Sample s;
    s.arm_q = p.arm;
    s.head_q = p.head;
    s.mono.found = true;
    s.mono.pose = (truth * headChain(model, p.head)).inverse() * model.marker(p.arm);
    s.mono.reprojection_error = 0.02;
    samples.push_back(s);
  }
  auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
  plan->method = "paper";
  plan->samples = 5;
  BlockHarness h("imagenets/SolveCalibration");
  h.set("description", path);
  h.input("samples", toSamplesMsg(samples)).input("plan", plan);
  h.run();
  // The description's own camera is the stereo pair: no sample has its observations.
  const Result as_stereo = fromMsg(*h.output<imagenets_calibration_msgs::CalibrationResult>("result"));
  EXPECT_FALSE(as_stereo.success);
  EXPECT_NE(as_stereo.message.find("marker not found (left: no detection; right: no detection)"), std::string::npos)
      << as_stereo.message;
  h.set("calibration_camera", std::string("mono"));
  h.run();
  const Result r = fromMsg(*h.output<imagenets_calibration_msgs::CalibrationResult>("result"));
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.samples[0].fusion, "mono");
  EXPECT_LT((r.fixed_point.translation() - truth.translation()).norm(), 1e-9);
  h.set("calibration_camera", std::string("left"));
  EXPECT_NE(h.runError().find("property 'calibration_camera': 'left' is no calibration camera"), std::string::npos);
}
