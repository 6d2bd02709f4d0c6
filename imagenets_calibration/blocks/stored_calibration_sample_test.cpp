#include <filesystem>

#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationPlan.h>
#include <std_msgs/Int32.h>
#include <imagenets_calibration_msgs/CalibrationSample.h>

#include "imagenets_calibration/storage.h"
#include "imagenets/blocks/block_harness.h"

using imagenets::blocks::BlockHarness;
using namespace imagenets_calibration;

TEST(StoredCalibrationSample, SampleKOfTheReplayFileAsMeasured) {
  const std::string file =
      (std::filesystem::temp_directory_path() / ("stored_sample_" + std::to_string(::getpid()) + ".yaml")).string();
  StoredCalibration stored;
  for (int k = 0; k < 3; ++k) {
    Sample s;
    s.arm_q.assign(7, 0.1 * k);
    s.head_q = {0.2, 0.3};
    s.left.found = true;
    s.left.pose.translation() = Eigen::Vector3d(0.01 * k, 0, 0.6);
    s.left.threshold = 80 + k;
    s.right.reason = "glare";
    s.stamp = 5.0 + k;
    stored.result.samples.push_back(s);
  }
  saveCalibration(stored, file);
  auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
  plan->replay_file = file;
  plan->samples = 3;
  auto k = boost::make_shared<std_msgs::Int32>();
  k->data = 2;
  BlockHarness h("imagenets/StoredCalibrationSample");
  h.input("plan", plan).input("repetition", k);
  h.run();
  const auto s = h.output<imagenets_calibration_msgs::CalibrationSample>("sample");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->arm_q, std::vector<double>(7, 0.2));
  EXPECT_EQ(s->left.threshold, 82);
  EXPECT_NEAR(s->left.pose.position.x, 0.02, 1e-12);
  EXPECT_EQ(s->right.reason, "glare");
  EXPECT_EQ(s->stamp, 7.0);
  // A plan of more samples than the file holds: the file is named.
  plan->samples = 5;
  k->data = 4;
  const std::string error = h.input("plan", plan).input("repetition", k).runError();
  EXPECT_NE(error.find(file + ": no sample 4 (it holds 3)"), std::string::npos) << error;
  std::filesystem::remove(file);
}

TEST(StoredCalibrationSample, ALivePlanIsNoReplay) {
  auto plan = boost::make_shared<imagenets_calibration_msgs::CalibrationPlan>();
  plan->samples = 1;
  BlockHarness h("imagenets/StoredCalibrationSample");
  EXPECT_NE(h.input("plan", plan).runError().find("not a replay plan"), std::string::npos);
}
