// rostest: friend_calibration_node against the simulated FRIEND robot. Starting from the nominal
// model it recovers the true fixed point (also with spurious-reflection outliers); every failure
// (marker not found, arm goal aborted, camera silent, concurrent trigger, cancel) leaves the saved
// calibration byte-identical; a replay of the stored samples reproduces the result.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <actionlib/client/simple_action_client.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/transform_listener.h>

#include "friend_hw_sim/true_robot.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration/storage.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets_calibration_msgs/CalibrateAction.h"
#include "imagenets/vision/frames.h"
#include "imagenets/calling_thread_queue.h"
#include "urdf_state_publisher.h"
#include "imagenets/package_file.h"

namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d toEigen(const geometry_msgs::Transform& t) { return imagenets::frames::toIsometry(t, "transform"); }

class FriendCalibration : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ros::NodeHandle pnh("~");
    file_ = pnh.param<std::string>("calibration_file", "");
  }
  void SetUp() override {
    ASSERT_TRUE(ros::service::waitForService("/friend_calibration/calibrate", ros::Duration(30)));
    resetFaults();
  }
  void TearDown() override { resetFaults(); }
  static void resetFaults() {
    for (const char* f : {"reflection_probability", "drop_frame_probability", "corrupt_frame_probability"}) {
      ros::param::set(std::string("/friend_sim/faults/") + f, 0.0);
    }
    ros::param::set("/friend_sim/faults/arm_abort_probability", 0.0);
    ros::param::set("/friend_sim/camera/illumination", 1.0);
    settle();
  }
  // The simulator reads its fault parameters through the parameter cache: give the update time
  // to arrive before the next goal.
  static void settle() { ros::WallDuration(0.3).sleep(); }
  imagenets_calibration_msgs::Calibrate::Response call(int redundancy, const std::string& replay = "") {
    imagenets_calibration_msgs::Calibrate srv;
    srv.request.redundancy = redundancy;
    srv.request.replay = replay;
    EXPECT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
    return srv.response;
  }
  // Error of a calibration against the simulator's true fixed point, and against the "effective"
  // one (the true mount with the pan encoder's zero offset folded in: a pan offset turns the whole
  // head about the mount's z, so no calibration of this frame can tell them apart).
  void errors(const geometry_msgs::TransformStamped& fixed, double* mm, double* deg, double* eff_mm, double* eff_deg) {
    auto truth = head_base_.wait(5);
    ASSERT_TRUE(truth);
    const Eigen::Isometry3d x = toEigen(fixed.transform), t = toEigen(truth->transform);
    *mm = (x.translation() - t.translation()).norm() * 1000;
    *deg = imagenets_calibration::angleBetween(x, t) / kDeg;
    std::string error_file;
    int seed = -1;
    ASSERT_TRUE(ros::param::get("/friend_sim/true_error", error_file));
    ros::param::get("/friend_sim/seed", seed);
    const auto error = friend_hw_sim::loadTrueError(
        error_file, robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml")), seed);
    const Eigen::Isometry3d effective =
        t * Eigen::AngleAxisd(error.head_joint_offsets.empty() ? 0.0 : error.head_joint_offsets[0], Eigen::Vector3d::UnitZ());
    *eff_mm = (x.translation() - effective.translation()).norm() * 1000;
    *eff_deg = imagenets_calibration::angleBetween(x, effective) / kDeg;
  }

  static std::string file_;
  LatestMessage<geometry_msgs::TransformStamped> head_base_{"/friend_sim/ground_truth/head_base"};
};
std::string FriendCalibration::file_;

TEST_F(FriendCalibration, RecoversTheTrueFixedPointAndPublishesIt) {
  const auto res = call(5);
  ASSERT_TRUE(res.success) << res.message;
  // The joint method visits two poses per loop: 10 samples for 5 loops.
  EXPECT_EQ(res.samples_used + res.samples_rejected, 10);
  EXPECT_GE(res.samples_used, 8) << res.message;
  EXPECT_EQ(res.file, file_);
  EXPECT_EQ(res.residual_translation.size(), 10u);
  double mm, deg, eff_mm, eff_deg;
  errors(res.fixed_point, &mm, &deg, &eff_mm, &eff_deg);
  std::printf("redundancy 5: error vs true mount %.3f mm / %.4f deg; vs effective fixed point %.3f mm / %.4f deg; "
              "std %.3f %.3f %.3f mm; %.3f s compute, %.2f s total\n",
              mm, deg, eff_mm, eff_deg, res.std_dev_translation.x * 1000, res.std_dev_translation.y * 1000,
              res.std_dev_translation.z * 1000, res.compute_time, res.total_time);
  EXPECT_LT(mm, 1.0);
  EXPECT_LT(eff_deg, 0.1);
  // The joint method's pixel-level fit ran on the node's detections and reports its uncertainty.
  EXPECT_NE(res.message.find("pixel-level bundle adjustment of"), std::string::npos) << res.message;
  const auto& c = res.fixed_point_covariance;
  const double bound_mm = 3000 * std::sqrt(c[0] + c[7] + c[14]), bound_deg = 3 * std::sqrt(c[21] + c[28] + c[35]) / kDeg;
  std::printf("reported uncertainty (3 sigma): %.3f mm / %.4f deg\n", bound_mm, bound_deg);
  EXPECT_GT(bound_mm, 0.0);
  EXPECT_LT(bound_mm, 2.0);
  // The default plan's poses determine every estimated parameter.
  EXPECT_TRUE(res.unobservable.empty()) << res.message;
  EXPECT_GT(res.condition_number, 1.0);
  EXPECT_TRUE(std::isfinite(res.condition_number));
  // Published on tf2: base_link -> pth_fixed_point equals the response.
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  geometry_msgs::TransformStamped tf;
  ASSERT_NO_THROW(tf = buffer.lookupTransform("base_link", "pth_fixed_point", ros::Time(0), ros::Duration(5)));
  EXPECT_NEAR(tf.transform.translation.x, res.fixed_point.transform.translation.x, 1e-9);
  EXPECT_NEAR(tf.transform.translation.z, res.fixed_point.transform.translation.z, 1e-9);
  // The calibrated camera frame hangs from it (paper 4.3).
  EXPECT_NO_THROW(buffer.lookupTransform("base_link", "calibrated/stereo_left_optical_frame", ros::Time(0), ros::Duration(5)));
}

// Like Fetch's robot_calibration, the node writes a calibrated URDF beside the calibration file:
// Debian's robot_state_publisher, started on it as it is, must give the calibrated frames: the
// head mount (base_link -> head_link_0) at the fixed point, and at given joint states the frames
// of the calibrated model (joint zero offsets and marker offset included).
TEST_F(FriendCalibration, CalibratedUrdfGivesTheCalibratedFramesInRobotStatePublisher) {
  const auto res = call(3);
  ASSERT_TRUE(res.success) << res.message;
  ASSERT_FALSE(res.urdf_file.empty()) << res.message;
  EXPECT_NE(res.message.find("calibrated URDF " + res.urdf_file), std::string::npos) << res.message;
  const imagenets_calibration::StoredCalibration stored = imagenets_calibration::loadCalibration(res.file);
  const imagenets_calibration::RobotModel calibrated = imagenets_calibration::calibratedModel(
      imagenets_calibration::RobotModel(robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml"))),
      stored.result);
  ASSERT_FALSE(stored.result.head_joint_offsets.empty()) << "the joint method estimates the tilt's zero offset";

  expectUrdfGivesTheFrames(res.urdf_file, calibrated, "head_link_0");
}

TEST_F(FriendCalibration, ReplayOfStoredSamplesReproducesTheResult) {
  const auto first = call(3);
  ASSERT_TRUE(first.success) << first.message;
  const std::string before = readFile(file_);
  const auto replay = call(0, file_);
  ASSERT_TRUE(replay.success) << replay.message;
  EXPECT_NEAR(replay.fixed_point.transform.translation.x, first.fixed_point.transform.translation.x, 1e-6);
  EXPECT_NEAR(replay.fixed_point.transform.translation.y, first.fixed_point.transform.translation.y, 1e-6);
  EXPECT_NEAR(replay.fixed_point.transform.translation.z, first.fixed_point.transform.translation.z, 1e-6);
  EXPECT_NEAR(replay.fixed_point.transform.rotation.w, first.fixed_point.transform.rotation.w, 1e-6);
  EXPECT_EQ(replay.rejected_samples, first.rejected_samples);
  EXPECT_EQ(readFile(file_), before) << "a replay must not write the calibration file";
}

TEST_F(FriendCalibration, OutliersFromSpuriousReflectionsAreRejected) {
  ros::param::set("/friend_sim/faults/reflection_probability", 0.3);
  settle();
  const auto res = call(5);
  ASSERT_TRUE(res.success) << res.message;
  double mm, deg, eff_mm, eff_deg;
  errors(res.fixed_point, &mm, &deg, &eff_mm, &eff_deg);
  std::printf("redundancy 5 with 30%% reflections: %d used, %d rejected; error %.3f mm / %.4f deg (effective %.3f mm / "
              "%.4f deg)\n",
              res.samples_used, res.samples_rejected, mm, deg, eff_mm, eff_deg);
  EXPECT_LT(mm, 1.0);
  EXPECT_LT(eff_deg, 0.1);
}

TEST_F(FriendCalibration, FailuresKeepThePreviousCalibrationByteIdentical) {
  if (readFile(file_).empty()) ASSERT_TRUE(call(1).success);
  const std::string before = readFile(file_);
  ASSERT_FALSE(before.empty());
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const auto tf_before = buffer.lookupTransform("base_link", "pth_fixed_point", ros::Time(0), ros::Duration(5));

  ros::param::set("/friend_sim/camera/illumination", 0.0);  // black images: no marker
  auto res = call(3);
  EXPECT_FALSE(res.success);
  EXPECT_NE(res.message.find("marker not found"), std::string::npos) << res.message;
  EXPECT_EQ(readFile(file_), before);
  resetFaults();

  ros::param::set("/friend_sim/faults/arm_abort_probability", 1.0);
  settle();
  res = call(3);
  EXPECT_FALSE(res.success);
  EXPECT_NE(res.message.find("/arm/move_joints' ABORTED"), std::string::npos) << res.message;  // the arm's goal
  EXPECT_EQ(readFile(file_), before);
  resetFaults();

  ros::param::set("/friend_sim/faults/drop_frame_probability", 1.0);
  settle();
  res = call(1);
  EXPECT_FALSE(res.success);
  EXPECT_NE(res.message.find("camera silent"), std::string::npos) << res.message;
  EXPECT_EQ(readFile(file_), before);
  resetFaults();

  res = call(4);
  EXPECT_FALSE(res.success);
  EXPECT_NE(res.message.find("odd"), std::string::npos) << res.message;
  EXPECT_EQ(readFile(file_), before);

  const auto tf_after = buffer.lookupTransform("base_link", "pth_fixed_point", ros::Time(0), ros::Duration(5));
  EXPECT_EQ(tf_after.transform.translation.x, tf_before.transform.translation.x);
  EXPECT_EQ(tf_after.transform.rotation.z, tf_before.transform.rotation.z);
}

TEST_F(FriendCalibration, ConcurrentTriggerIsRejectedAndCancelKeepsTheFile) {
  if (readFile(file_).empty()) ASSERT_TRUE(call(1).success);
  const std::string before = readFile(file_);
  int feedback_sample = 0, feedback_of = 0;  // written by the feedback callback, in clients.waitUntil
  imagenets::CallingThreadQueue clients;     // called back only in its waitUntil (it says why)
  actionlib::SimpleActionClient<imagenets_calibration_msgs::CalibrateAction> client(clients.nodeHandle(),
                                                                   "/friend_calibration/calibrate_action", false);
  ASSERT_TRUE(clients.waitUntil([&client] { return client.isServerConnected(); }, 10));
  imagenets_calibration_msgs::CalibrateGoal goal;
  goal.redundancy = 9;
  client.sendGoal(goal, {}, {}, [&](const imagenets_calibration_msgs::CalibrateFeedbackConstPtr& f) {
    feedback_sample = f->sample;
    feedback_of = f->samples;
  });
  // Wait until the action reports that it is sampling.
  clients.waitUntil([&] { return feedback_sample >= 1; }, 20);
  EXPECT_GE(feedback_sample, 1);
  EXPECT_EQ(feedback_of, 18);
  const auto res = call(1);
  EXPECT_FALSE(res.success);
  EXPECT_NE(res.message.find("already running"), std::string::npos) << res.message;
  client.cancelGoal();
  ASSERT_TRUE(clients.waitUntil([&client] { return client.getState().isDone(); }, 30));
  EXPECT_EQ(client.getState(), actionlib::SimpleClientGoalState::PREEMPTED) << client.getState().getText();
  EXPECT_NE(client.getResult()->message.find("cancelled"), std::string::npos) << client.getResult()->message;
  EXPECT_EQ(readFile(file_), before);
}

TEST_F(FriendCalibration, ThePosesFieldOfTheGoalTakesThatManySamples) {
  int feedback_of = 0;
  imagenets::CallingThreadQueue clients;
  actionlib::SimpleActionClient<imagenets_calibration_msgs::CalibrateAction> client(clients.nodeHandle(),
                                                                   "/friend_calibration/calibrate_action", false);
  ASSERT_TRUE(clients.waitUntil([&client] { return client.isServerConnected(); }, 10));
  imagenets_calibration_msgs::CalibrateGoal goal;
  goal.poses = 3;  // redundancy 0: the node's default (5 loops) would be 10
  client.sendGoal(goal, {}, {}, [&](const imagenets_calibration_msgs::CalibrateFeedbackConstPtr& f) { feedback_of = f->samples; });
  ASSERT_TRUE(clients.waitUntil([&client] { return client.getState().isDone(); }, 180));
  const auto res = client.getResult();
  ASSERT_TRUE(res);
  EXPECT_EQ(feedback_of, 3);
  EXPECT_EQ(res->samples_used + res->samples_rejected, 3) << res->message;
  EXPECT_EQ(res->residual_translation.size(), 3u) << res->message;
  // Whether or not the node keeps it (~max_uncertainty), the result says what its poses determined.
  EXPECT_GT(res->condition_number, 0.0) << res->message;
  EXPECT_NE(res->message.find("condition number"), std::string::npos) << res->message;
  // A negative count is named.
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.poses = -2;
  ASSERT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("request field 'poses' is -2"), std::string::npos) << srv.response.message;
}

TEST_F(FriendCalibration, AnUncertaintyTargetAddsThePlansNextPosesUntilItIsMet) {
  // Six poses give about 0.7 mm (3 sigma) here, ten about 0.3 mm: a 0.4 mm target needs more
  // than the six asked for. Met, or (bad luck with the noise) said not to be at max_poses.
  const double target = 0.0004;
  const int requested = 6, max_poses = 14;
  std::vector<std::pair<int, double>> bounds;  // (poses so far, 3 sigma) fed back after each check
  imagenets::CallingThreadQueue clients;
  actionlib::SimpleActionClient<imagenets_calibration_msgs::CalibrateAction> client(clients.nodeHandle(),
                                                                   "/friend_calibration/calibrate_action", false);
  // Every sample's stereo pair is drawn with its detections, also those after which the until net
  // was asked for the bound (a latched topic: what came before the goal is not counted).
  bool sent = false;
  int drawn = 0;
  ros::Subscriber drawings = clients.nodeHandle().subscribe<sensor_msgs::Image>(
      "/friend_calibration/detections/left/image", 20, [&](const sensor_msgs::ImageConstPtr&) { drawn += sent; });
  ASSERT_TRUE(clients.waitUntil([&client] { return client.isServerConnected(); }, 10));
  clients.waitUntil([] { return false; }, 1.0);  // the latched image of an earlier test, if any
  imagenets_calibration_msgs::CalibrateGoal goal;
  goal.poses = requested;
  goal.target_uncertainty = target;
  goal.max_poses = max_poses;
  sent = true;
  client.sendGoal(goal, {}, {}, [&](const imagenets_calibration_msgs::CalibrateFeedbackConstPtr& f) {
    EXPECT_EQ(f->samples, max_poses);
    if (f->stage == "uncertainty") bounds.emplace_back(f->sample, f->uncertainty);
  });
  ASSERT_TRUE(clients.waitUntil([&client] { return client.getState().isDone(); }, 180));
  const auto res = client.getResult();
  ASSERT_TRUE(res);
  std::printf("target %.3f mm: %d poses taken, 3 sigma %.3f mm / %.4f deg, target %s\n", target * 1000,
              res->poses_taken, res->uncertainty * 1000, res->uncertainty_rotation / kDeg, res->target_met ? "met" : "NOT met");
  for (const auto& [k, b] : bounds) std::printf("  after %d poses: 3 sigma %.3f mm\n", k, b * 1000);
  ASSERT_TRUE(res->success) << res->message;
  EXPECT_GT(res->poses_taken, requested) << res->message;
  EXPECT_LE(res->poses_taken, max_poses) << res->message;
  EXPECT_EQ(res->samples_used + res->samples_rejected, res->poses_taken) << res->message;
  EXPECT_TRUE(clients.waitUntil([&] { return drawn >= res->poses_taken; }, 5)) << drawn << " drawings";
  EXPECT_EQ(drawn, res->poses_taken);
  EXPECT_GT(res->uncertainty, 0.0);
  if (res->target_met) {
    EXPECT_LE(res->uncertainty, target) << res->message;
    EXPECT_NE(res->message.find("uncertainty target met"), std::string::npos) << res->message;
  } else {
    EXPECT_EQ(res->poses_taken, max_poses) << res->message;
    EXPECT_GT(res->uncertainty, target) << res->message;
    EXPECT_NE(res->message.find("uncertainty target NOT met"), std::string::npos) << res->message;
  }
  // The feedback: the bound after the six asked for, and after each pose added; it continued
  // because the bound was still above the target.
  // (Checked after each pose up to the last one that may still be followed by another.)
  const int last_check = res->target_met ? res->poses_taken : max_poses - 1;
  ASSERT_TRUE(clients.waitUntil([&] { return !bounds.empty() && bounds.back().first >= last_check; }, 10));
  EXPECT_EQ(bounds.front().first, requested);
  EXPECT_EQ(bounds.back().first, last_check);
  // The check solves what the final solve solves: the same bound.
  if (res->target_met) EXPECT_NEAR(bounds.back().second, res->uncertainty, 1e-9);
  for (size_t i = 0; i + 1 < bounds.size(); ++i) {
    EXPECT_EQ(bounds[i + 1].first, bounds[i].first + 1);
    EXPECT_GT(bounds[i].second, target) << "after " << bounds[i].first << " poses";
  }

  // Bad requests are named, and fail before the robot moves.
  imagenets_calibration_msgs::Calibrate srv;
  srv.request.target_uncertainty = -0.001;
  ASSERT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("request field 'target_uncertainty' is -0.001"), std::string::npos)
      << srv.response.message;
  srv.request.target_uncertainty = 0.001;
  srv.request.method = "paper";
  ASSERT_TRUE(ros::service::call("/friend_calibration/calibrate", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("an uncertainty target needs the joint method"), std::string::npos)
      << srv.response.message;
  EXPECT_EQ(srv.response.poses_taken, 0) << srv.response.message;
}

TEST(FriendCalibrationNet, ABadNetIsNamedAndTheNodeKeepsServing) {
  for (const auto& [node, culprit] : std::vector<std::pair<std::string, std::string>>{
           {"/friend_calibration_missing_net", "/nonexistent/calibration.yaml"},
           {"/friend_calibration_wrong_net", "threshold_demo.yaml: no block 'plan'"}}) {
    ASSERT_TRUE(ros::service::waitForService(node + "/calibrate", ros::Duration(30))) << node;
    imagenets_calibration_msgs::Calibrate srv;
    srv.request.redundancy = 1;
    ASSERT_TRUE(ros::service::call(node + "/calibrate", srv)) << node;
    EXPECT_FALSE(srv.response.success);
    EXPECT_NE(srv.response.message.find("the calibration net is not usable"), std::string::npos) << srv.response.message;
    EXPECT_NE(srv.response.message.find(culprit), std::string::npos) << srv.response.message;
    EXPECT_NE(srv.response.message.find("unchanged"), std::string::npos) << srv.response.message;
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_calibration_rostest");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
