// rostest: a live calibration recorded into a rosbag, then calibrated from the bag offline with
// `imagenets calibrate --bag` (no master): the same result to 1e-9 (see friend_calibration_bag.test).
#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "imagenets_calibration/storage.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets/testing/command_runner.h"
#include "imagenets/testing/rostest_util.h"
#include "files_and_processes.h"

namespace {

// The node's default calibration (redundancy 5, joint method), as a user asks for it.
imagenets_calibration_msgs::Calibrate::Response calibrate() {
  return callService<imagenets_calibration_msgs::Calibrate>("/calibration/calibrate");
}

TEST(FriendCalibrationBag, OfflineFromTheRecordedBagEqualsTheLiveRun) {
  ASSERT_TRUE(ros::service::waitForService("/calibration/calibrate", ros::Duration(60)));
  std::string description, dir;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("description", description));
  ASSERT_TRUE(ros::NodeHandle("~").getParam("dir", dir));
  const std::string bag = dir + "/calibration.bag";

  const auto live = calibrate();
  ASSERT_TRUE(live.success) << live.message;
  EXPECT_NE(live.message.find("recorded to " + bag), std::string::npos) << live.message;
  std::ifstream recorded(bag);
  ASSERT_TRUE(recorded.good()) << bag;
  EXPECT_FALSE(std::ifstream(dir + "/calibration.tmp.bag").good()) << "temporary bag left behind";

  // Offline, with a master that does not exist: the bag is all it needs.
  const std::string offline_file = dir + "/offline.yaml";
  const imagenets::testing::CommandResult result = imagenets::testing::runCommand(
      "ROS_MASTER_URI=http://127.0.0.1:9 " IMAGENETS_TOOL,
      "calibrate --bag " + bag + " --config " + description + " --output " + offline_file);
  const int status = result.status;
  const std::string& out = result.output;
  std::printf("imagenets calibrate --bag %s:\n%s", bag.c_str(), out.c_str());
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("bag: 10 samples"), std::string::npos) << out;

  const auto a = imagenets_calibration::loadCalibration(live.file).result;
  const auto b = imagenets_calibration::loadCalibration(offline_file).result;
  EXPECT_EQ(a.used, b.used);
  EXPECT_EQ(a.rejected, b.rejected);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  double diff = 0;
  auto compare = [&](const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
    ASSERT_EQ(x.rows(), y.rows());
    ASSERT_EQ(x.cols(), y.cols());
    diff = std::max(diff, (x - y).cwiseAbs().maxCoeff());
  };
  compare(a.fixed_point.matrix(), b.fixed_point.matrix());
  compare(a.marker_offset.matrix(), b.marker_offset.matrix());
  compare(a.fixed_point_covariance, b.fixed_point_covariance);
  compare(Eigen::Map<const Eigen::VectorXd>(a.arm_joint_offsets.data(), a.arm_joint_offsets.size()),
          Eigen::Map<const Eigen::VectorXd>(b.arm_joint_offsets.data(), b.arm_joint_offsets.size()));
  compare(Eigen::Map<const Eigen::VectorXd>(a.head_joint_offsets.data(), a.head_joint_offsets.size()),
          Eigen::Map<const Eigen::VectorXd>(b.head_joint_offsets.data(), b.head_joint_offsets.size()));
  for (size_t k = 0; k < a.samples.size(); ++k) {
    EXPECT_EQ(a.samples[k].arm_q, b.samples[k].arm_q) << "sample " << k;
    EXPECT_EQ(a.samples[k].head_q, b.samples[k].head_q) << "sample " << k;
    EXPECT_EQ(a.samples[k].stamp, b.samples[k].stamp) << "sample " << k;
    EXPECT_EQ(a.samples[k].left.found, b.samples[k].left.found) << "sample " << k;
    EXPECT_EQ(a.samples[k].right.found, b.samples[k].right.found) << "sample " << k;
  }
  const Eigen::Vector3d t = a.fixed_point.translation();
  std::printf("live vs offline from the recorded bag: %zu samples, %zu used; fixed point [%.6f %.6f %.6f] m; "
              "largest difference of fixed point, marker offset, joint offsets, covariance: %.3g\n",
              a.samples.size(), a.used.size(), t.x(), t.y(), t.z(), diff);
  EXPECT_LE(diff, 1e-9);

  // A failed live run (an aborting arm controller) leaves the recorded bag byte for byte.
  const std::string saved = readFile(bag);
  ros::param::set("/friend_sim/faults/arm_abort_probability", 1.0);
  const auto failed = calibrate();
  ros::param::set("/friend_sim/faults/arm_abort_probability", 0.0);
  EXPECT_FALSE(failed.success);
  EXPECT_EQ(readFile(bag), saved);
  EXPECT_FALSE(std::ifstream(dir + "/calibration.tmp.bag").good()) << "temporary bag left behind";
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_calibration_bag_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
