// The calibration as a net (config/nets/calibration.yaml): replaying a stored calibration through
// it -- the replay sample net repeated once per stored sample, then SolveCalibration -- gives the
// library's calibrate() result on the same samples, for both methods; bad replay input is a
// named error.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>
#include <imagenets_calibration_msgs/CalibrationResult.h>

#include "imagenets_calibration/calibration_msgs.h"
#include "imagenets_calibration/storage.h"
#include "imagenets/executor.h"
#include "imagenets/net.h"
#include "imagenets/package_file.h"
#include "imagenets/testing/read_file.h"

namespace imagenets_calibration {
namespace {

namespace fs = std::filesystem;

std::string netsDir() {
  return imagenets::packageFile("friend_calibration", "config/nets/");
}

struct CalibrationNet : ::testing::Test {
  RobotModel model{robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"))};
  fs::path dir = fs::temp_directory_path() / ("calibration_net_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  // Samples of the joint method's poses seen with a true fixed point and marker offset that differ
  // from nominal, with noise, varied reprojection errors (one over the gate), a marker not found,
  // and a spurious detection (outlier): every branch of the solve has work.
  std::string storedFile() {
    Eigen::Isometry3d truth = model.headBase();
    truth.translation() += Eigen::Vector3d(0.006, -0.004, 0.005);
    truth.rotate(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()));
    Eigen::Isometry3d marker_offset = model.description().marker.pose;
    marker_offset.translation() += Eigen::Vector3d(0.0008, 0, 0);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0, 0.0001);
    std::vector<Sample> samples;
    const auto poses = calibrationPoses(model, 10, "joint");
    for (size_t k = 0; k < poses.size(); ++k) {
      Sample s;
      s.arm_q = poses[k].arm;
      s.head_q = poses[k].head;
      s.stamp = 10.0 + k;
      const Eigen::Isometry3d seen = (truth * headChain(model, s.head_q)).inverse() * model.tcp(s.arm_q) * marker_offset;
      for (MarkerObservation* o : {&s.left, &s.right}) {
        o->found = true;
        o->pose = o == &s.left ? seen : model.leftToRight().inverse() * seen;
        o->pose.translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        o->confidence = 0.95;
        o->threshold = 100 + k;
        o->reprojection_error = 0.01 + 0.003 * k;
        o->points.assign(8, Eigen::Vector2d(500 + k, 400 - k));
      }
      samples.push_back(s);
    }
    samples[2].right.reprojection_error = 0.4;  // gated: the left one is used alone
    samples[5].left.found = samples[5].right.found = false;
    samples[5].left.reason = samples[5].right.reason = "no valid candidate";
    samples[7].left.pose.translation().y() += 0.02;  // a spurious detection, in both images
    samples[7].right.pose.translation().y() += 0.02;
    StoredCalibration stored;
    stored.result.samples = samples;
    stored.result.method = "joint";
    const std::string file = (dir / "stored.yaml").string();
    saveCalibration(stored, file);
    return file;
  }

  imagenets_calibration_msgs::CalibrationResult::ConstPtr replay(const std::string& file, const std::string& method) {
    imagenets::NetSpec spec = imagenets::parseNetFile(netsDir() + "calibration.yaml");
    spec.block("samples").setProperty("net", imagenets::packageFile("imagenets_calibration", "config/nets/calibration_sample_replay.yaml"));
    spec.block("plan").setProperty("replay", file);
    spec.block("plan").setProperty("method", method);
    imagenets::Executor exec(imagenets::Net::build(spec), imagenets::ExecutorOptions{2});
    const imagenets::RunReport report = exec.run();
    EXPECT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed.front());
    return exec.output<imagenets_calibration_msgs::CalibrationResult>("result.value");
  }
};

TEST_F(CalibrationNet, ReplayThroughTheNetGivesTheLibrarysResultForBothMethods) {
  const std::string file = storedFile();
  const std::vector<Sample> stored = loadCalibration(file).result.samples;
  for (const std::string method : {"paper", "joint"}) {
    CombineOptions combine;
    combine.min_valid_samples = static_cast<int>(std::ceil(0.5 * stored.size()));
    const Result library = calibrate(model, stored, method, FusionLimits(), combine);
    ASSERT_TRUE(library.success) << library.message;
    const auto msg = replay(file, method);
    ASSERT_TRUE(msg) << method;
    const Result net = fromMsg(*msg);
    ASSERT_TRUE(net.success) << net.message;
    EXPECT_EQ(net.method, method);
    EXPECT_LT((net.fixed_point.translation() - library.fixed_point.translation()).norm(), 1e-9) << method;
    // (Rotation matrices compared: an angle from acos resolves only ~2e-8 rad.)
    EXPECT_LT((net.fixed_point.rotation() - library.fixed_point.rotation()).norm(), 1e-9) << method;
    EXPECT_LT((net.marker_offset.translation() - library.marker_offset.translation()).norm(), 1e-9) << method;
    EXPECT_LT((net.std_translation - library.std_translation).norm(), 1e-9) << method;
    EXPECT_EQ(net.used, library.used) << method;
    EXPECT_EQ(net.rejected, library.rejected) << method;
    EXPECT_EQ(net.rejection_reasons, library.rejection_reasons) << method;
    ASSERT_EQ(net.samples.size(), stored.size());
    for (size_t i = 0; i < stored.size(); ++i) {
      EXPECT_EQ(net.samples[i].valid, library.samples[i].valid) << method << " sample " << i;
      EXPECT_EQ(net.samples[i].reason, library.samples[i].reason) << method << " sample " << i;
      if (std::isfinite(library.residual_translation[i])) {
        EXPECT_NEAR(net.residual_translation[i], library.residual_translation[i], 1e-9) << method << " sample " << i;
      }
    }
    for (size_t j = 0; j < library.arm_joint_offsets.size(); ++j) {
      EXPECT_NEAR(net.arm_joint_offsets[j], library.arm_joint_offsets[j], 1e-9) << method;
    }
    // The method's own work is visible: the gated detection, the lost marker, the outlier.
    EXPECT_EQ(net.samples[2].fusion, "left") << net.samples[2].reason;
    EXPECT_NE(net.samples[5].reason.find("marker not found"), std::string::npos) << net.samples[5].reason;
    EXPECT_NE(std::find(net.rejected.begin(), net.rejected.end(), 7), net.rejected.end()) << method;
  }
}

TEST_F(CalibrationNet, ABadReplayFileIsANamedError) {
  const std::string file = storedFile();
  std::string text = imagenets::testing::readFile(file);
  // Sample 3's arm joints become a word.
  const auto at = text.find("arm_q", text.find("arm_q", text.find("arm_q", text.find("arm_q") + 1) + 1) + 1);
  ASSERT_NE(at, std::string::npos);
  const auto open = text.find('[', at), close = text.find(']', at);
  text.replace(open, close - open + 1, "[elbow]");
  std::ofstream(file) << text;
  imagenets::NetSpec spec = imagenets::parseNetFile(netsDir() + "calibration.yaml");
  spec.block("samples").setProperty("net", imagenets::packageFile("imagenets_calibration", "config/nets/calibration_sample_replay.yaml"));
  spec.block("plan").setProperty("replay", file);
  imagenets::Executor exec(imagenets::Net::build(spec), imagenets::ExecutorOptions{2});
  const imagenets::RunReport report = exec.run();
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.failed.front().find(file), std::string::npos) << report.failed.front();
  EXPECT_NE(report.failed.front().find("block 'plan'"), std::string::npos) << report.failed.front();
}

}  // namespace
}  // namespace imagenets_calibration
