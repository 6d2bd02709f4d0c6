// rostest: the simulated FRIEND calibrated through control_msgs/FollowJointTrajectory only, with
// the generic nets of imagenets_calibration (see friend_calibration_trajectory.test).
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/ros.h>

#include "friend_hw_sim/true_robot.h"
#include "imagenets/vision/frames.h"
#include "imagenets_calibration/calibration.h"
#include "imagenets_calibration_msgs/Calibrate.h"
#include "imagenets/testing/rostest_util.h"
#include "files_and_processes.h"
#include "robot_description/robot_model.h"

namespace {

constexpr double kDeg = M_PI / 180.0;
// The calibration's targets for one run (joint method, redundancy 5), as on the six-axis robot.
constexpr double kTargetMm = 0.5, kTargetDeg = 0.05;

// The node's default calibration (redundancy 5, joint method), as a user asks for it.
imagenets_calibration_msgs::Calibrate::Response calibrate() {
  return callService<imagenets_calibration_msgs::Calibrate>("/calibration/calibrate");
}

TEST(FriendCalibrationTrajectory, TheRobotServesOnlyTheStandardMotionInterface) {
  // The calibration node answers once the simulator runs: its servers are advertised by then.
  ASSERT_TRUE(ros::service::waitForService("/calibration/calibrate", ros::Duration(60)));
  bool arm = false, head = false;
  for (int attempt = 0; attempt < 300 && !(arm && head); ++attempt) {
    if (attempt > 0) ros::WallDuration(0.1).sleep();
    ros::master::V_TopicInfo topics;
    ASSERT_TRUE(ros::master::getTopics(topics));
    arm = head = false;
    for (const auto& t : topics) {
      EXPECT_EQ(t.name.find("/move_joints/"), std::string::npos) << t.name << ": the simulator serves MoveJoints";
      arm = arm || t.name == "/arm_controller/follow_joint_trajectory/status";
      head = head || t.name == "/head_controller/follow_joint_trajectory/status";
    }
  }
  EXPECT_TRUE(arm && head) << "no FollowJointTrajectory servers for arm and head";
}

TEST(FriendCalibrationTrajectory, CalibratesWithinTheTargetsInsideTheReportedBound) {
  ASSERT_TRUE(ros::service::waitForService("/calibration/calibrate", ros::Duration(60)));
  const auto res = calibrate();
  ASSERT_TRUE(res.success) << res.message;
  EXPECT_EQ(res.samples_used + res.samples_rejected, 10);
  EXPECT_TRUE(res.unobservable.empty()) << res.message;

  // Against the simulator's truth, as the six-axis rostest measures it (friend_hw_sim/true_robot.h).
  std::string description, error_file;
  ASSERT_TRUE(ros::NodeHandle("~").getParam("description", description));
  ASSERT_TRUE(ros::param::get("/friend_sim/true_error", error_file));
  const auto nominal = robot_description::loadRobotDescription(description);
  const auto truth = friend_hw_sim::loadTrueError(error_file, nominal, -1);
  const Eigen::Isometry3d x = imagenets::frames::toIsometry(res.fixed_point.transform, "fixed point");
  const Eigen::Isometry3d identifiable = friend_hw_sim::identifiableHeadBase(nominal, truth);
  const double mm = (x.translation() - identifiable.translation()).norm() * 1000;
  const double deg = imagenets_calibration::angleBetween(x, identifiable) / kDeg;
  const auto& c = res.fixed_point_covariance;
  const double bound_mm = 3000 * std::sqrt(c[0] + c[7] + c[14]), bound_deg = 3 * std::sqrt(c[21] + c[28] + c[35]) / kDeg;
  std::printf("FRIEND through FollowJointTrajectory only: error vs identifiable fixed point %.3f mm / %.4f deg; "
              "reported 3 sigma %.3f mm / %.4f deg; %d of %d samples used; %.2f s total\n",
              mm, deg, bound_mm, bound_deg, res.samples_used, res.samples_used + res.samples_rejected, res.total_time);
  EXPECT_LT(mm, kTargetMm);
  EXPECT_LT(deg, kTargetDeg);
  EXPECT_LT(mm, bound_mm);
  EXPECT_LT(deg, bound_deg);

  // A controller that aborts (the joint that moves most sticks part way: a path or, when it stuck
  // within the path tolerance, a goal tolerance violation): the calibration fails with the
  // controller's reason naming the joint, and the saved calibration stays byte for byte.
  const std::string saved = readFile(res.file);
  ASSERT_FALSE(saved.empty());
  ros::param::set("/friend_sim/faults/arm_abort_probability", 1.0);  // read at each goal
  const auto failed = calibrate();
  ros::param::set("/friend_sim/faults/arm_abort_probability", 0.0);
  EXPECT_FALSE(failed.success);
  std::printf("with an aborting arm controller: %s\n", failed.message.c_str());
  EXPECT_TRUE(failed.message.find("PATH_TOLERANCE_VIOLATED") != std::string::npos ||
              failed.message.find("GOAL_TOLERANCE_VIOLATED") != std::string::npos)
      << failed.message;
  EXPECT_NE(failed.message.find("ABORTED"), std::string::npos) << failed.message;
  EXPECT_NE(failed.message.find("joint 'arm_joint_"), std::string::npos) << failed.message;
  EXPECT_NE(failed.message.find("/arm_controller/follow_joint_trajectory"), std::string::npos) << failed.message;
  EXPECT_EQ(readFile(res.file), saved);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_calibration_trajectory_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
