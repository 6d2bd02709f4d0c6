// Samples from rosbags: a teleoperation-style bag (joint_states streaming, the robot moving between
// still periods, images at camera rate) gives one sample per still period and says why the other
// images were skipped; a bag as the node records it (one joint reading per sample, at its image)
// gives every sample, even two at one pose; a bag without a needed topic names it; the recorder
// puts a bag in place only on commit.
#include "imagenets_calibration/bag_samples.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "imagenets_calibration/bag_calibration.h"
#include "imagenets_calibration/bag_recorder.h"
#include "imagenets_calibration/calibration.h"

namespace imagenets_calibration {
namespace {

namespace fs = std::filesystem;

struct BagSamplesTest : ::testing::Test {
  RobotModel model{robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath())};
  std::vector<std::string> joints = sampleJoints(model);
  fs::path dir = fs::temp_directory_path() / ("calib_bags_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  sensor_msgs::Image image(double t) {
    sensor_msgs::Image img;
    img.header.stamp.fromSec(t);
    img.width = img.height = img.step = 1;
    img.encoding = "mono8";
    img.data = {static_cast<uint8_t>(static_cast<int>(t * 10) % 256)};
    return img;
  }
  sensor_msgs::JointState reading(double t, double q) {
    sensor_msgs::JointState js;
    js.header.stamp.fromSec(t);
    js.name = joints;
    js.position.assign(joints.size(), q);
    return js;
  }
  void writePair(BagRecorder& bag, double t, bool right = true) {
    const ros::Time time = ros::Time().fromSec(t);
    sensor_msgs::CameraInfo info;
    info.header.stamp = time;
    bag.write("/stereo/left/image_raw", time, image(t));
    if (right) bag.write("/stereo/right/image_raw", time, image(t));
    bag.write("/stereo/left/camera_info", time, info);
    bag.write("/stereo/right/camera_info", time, info);
  }
};

TEST_F(BagSamplesTest, TeleoperationBagGivesOneSamplePerStillPeriod) {
  const std::string file = (dir / "teleop.bag").string();
  BagRecorder bag(file);
  // 0-2 s still at 0.1, 2-3 s moving to 0.3, 3-5 s still, 5-6 s moving to 0.5, 6-8 s still.
  auto q = [](double t) {
    if (t < 2) return 0.1;
    if (t < 3) return 0.1 + 0.2 * (t - 2);
    if (t < 5) return 0.3;
    if (t < 6) return 0.3 + 0.2 * (t - 5);
    return 0.5;
  };
  for (int i = 0; i <= 400; ++i) {  // 50 Hz joint_states
    const double t = 100 + i * 0.02;
    bag.write("/joint_states", ros::Time().fromSec(t), reading(t, q(t - 100)));
  }
  for (int i = 0; i < 80; ++i) {  // 10 Hz stereo pairs, one without its right image
    const double t = 100.05 + i * 0.1;
    writePair(bag, t, i != 10);
  }
  bag.commit();
  const auto samples = readBagSamples(file, joints, BagSampleSettings());
  ASSERT_EQ(samples->samples.size(), 3u) << samples->report;
  EXPECT_DOUBLE_EQ(samples->samples[0].joints->position[0], 0.1);
  EXPECT_DOUBLE_EQ(samples->samples[1].joints->position[0], 0.3);
  EXPECT_DOUBLE_EQ(samples->samples[2].joints->position.back(), 0.5);
  for (const auto& s : samples->samples) {
    ASSERT_TRUE(s.left && s.right && s.left_info && s.right_info);
    EXPECT_EQ(s.left->header.stamp, s.right->header.stamp);
    EXPECT_EQ(s.joints->name, joints);
  }
  EXPECT_NE(samples->report.find("3 samples"), std::string::npos) << samples->report;
  EXPECT_NE(samples->report.find("while joints moved"), std::string::npos) << samples->report;
  EXPECT_NE(samples->report.find("1 without a right image"), std::string::npos) << samples->report;
  std::printf("teleoperation bag: %s\n", samples->report.c_str());
}

TEST_F(BagSamplesTest, NodeBagGivesEverySampleEvenTwoAtOnePose) {
  const std::string file = (dir / "node.bag").string();
  BagRecorder bag(file);
  const std::vector<double> poses{0.1, 0.2, 0.2, 0.3};
  for (size_t k = 0; k < poses.size(); ++k) {
    const double t = 10 + 1.5 * k;
    writePair(bag, t);
    bag.write("/joint_states", ros::Time().fromSec(t), reading(t, poses[k]));
  }
  bag.commit();
  const auto samples = readBagSamples(file, joints, BagSampleSettings());
  ASSERT_EQ(samples->samples.size(), 4u) << samples->report;
  for (size_t k = 0; k < poses.size(); ++k) {
    EXPECT_EQ(samples->samples[k].joints->position[0], poses[k]);
    EXPECT_DOUBLE_EQ(samples->samples[k].left->header.stamp.toSec(), 10 + 1.5 * k);
  }
}

TEST_F(BagSamplesTest, BagWithoutANeededTopicNamesIt) {
  const std::string file = (dir / "joints_only.bag").string();
  BagRecorder bag(file);
  bag.write("/joint_states", ros::Time(1), reading(1, 0.1));
  bag.commit();
  try {
    readBagSamples(file, joints, BagSampleSettings());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no topic '/stereo/left/image_raw'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the bag has /joint_states"), std::string::npos) << e.what();
  }
  // Through the whole offline calibration: the same error, before any net runs.
  BagCalibrationOptions o;
  o.bag = file;
  o.description = robot_description::exampleRobotDescriptionPath();
  try {
    calibrateFromBag(o);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no topic '/stereo/left/image_raw'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readBagSamples((dir / "none.bag").string(), joints, BagSampleSettings()), std::runtime_error);
}

TEST_F(BagSamplesTest, RecorderReplacesTheBagOnlyOnCommit) {
  const fs::path file = dir / "calibration.bag";
  {
    BagRecorder first(file.string());
    first.write("/joint_states", ros::Time(1), reading(1, 0.1));
    first.commit();
  }
  const auto size = fs::file_size(file);
  {
    BagRecorder failed(file.string());
    for (int i = 0; i < 100; ++i) failed.write("/joint_states", ros::Time(2 + i), reading(2 + i, 0.2));
    EXPECT_TRUE(fs::exists(dir / "calibration.tmp.bag"));
  }  // a failed run: never committed
  EXPECT_FALSE(fs::exists(dir / "calibration.tmp.bag"));
  EXPECT_EQ(fs::file_size(file), size);
}

}  // namespace
}  // namespace imagenets_calibration
