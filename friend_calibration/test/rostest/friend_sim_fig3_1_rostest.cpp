// rostest: the Fig. 3.1 nodelet net moved the arm to its configuration and turned the head to
// look at the TCP; the TCP is then near the stereo image centre of the true cameras.
#include <cmath>
#include <cstdio>

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/JointState.h>
#include <tf2_eigen/tf2_eigen.h>

#include "robot_description/robot_model.h"
#include "imagenets/package_file.h"

namespace {

TEST(FriendSimFig31, HeadLooksAtTheTcpAfterTheArmMoved) {
  const robot_description::RobotModel nominal(
      robot_description::loadRobotDescription(imagenets::packageFile("friend_description", "config/robot.yaml")));
  const auto& d = nominal.description();
  const std::vector<double> arm_target{-35, 63, 83, 79, -22, 74, 0};
  std::vector<double> arm_rad;
  for (double a : arm_target) arm_rad.push_back(a * M_PI / 180);
  const auto head_target = nominal.lookAt(nominal.tcp(arm_rad).translation(), {0.0, 0.5});

  // Wait (bounded) until joint_states show arm and head where the net should leave them. The
  // simulator may start seconds after this test on a loaded machine (a 2 s wait for the first
  // message failed 1 in 6 sweep runs): every wait is generous.
  sensor_msgs::JointStateConstPtr js;
  double worst = 1e9;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(90);
  while (ros::WallTime::now() < end) {
    js = ros::topic::waitForMessage<sensor_msgs::JointState>("joint_states", ros::Duration(30));
    ASSERT_TRUE(js) << "no joint_states within 30 s";
    worst = 0;
    for (int i = 0; i < 7; ++i) worst = std::max(worst, std::abs(js->position[i] - arm_rad[i]));
    for (int i = 0; i < 2; ++i) worst = std::max(worst, std::abs(js->position[7 + i] - head_target[i]));
    bool still = true;
    for (double v : js->velocity) still = still && v == 0.0;
    if (worst < 1e-9 && still) break;
  }
  ASSERT_LT(worst, 1e-9) << "arm/head did not reach the Fig. 3.1 configuration";

  const auto tcp = ros::topic::waitForMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/tcp", ros::Duration(30));
  const auto left = ros::topic::waitForMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/left_camera", ros::Duration(30));
  const auto right = ros::topic::waitForMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/right_camera", ros::Duration(30));
  ASSERT_TRUE(tcp && left && right);
  double mid_x = 0, mid_y = 0;
  for (const auto& cam : {left, right}) {
    const Eigen::Vector3d p = tf2::transformToEigen(*cam).inverse() * tf2::transformToEigen(*tcp).translation();
    ASSERT_GT(p.z(), 0.2);
    mid_x += (1400.0 * p.x() / p.z() + 512) / 2;
    mid_y += (1400.0 * p.y() / p.z() + 384) / 2;
  }
  const double off = std::hypot(mid_x - 512, mid_y - 384);
  std::printf("Fig. 3.1 (nodelets): TCP stereo midpoint %.1f px from the image centre\n", off);
  EXPECT_LT(off, 100.0);  // a ~2 deg head-mount error: tens of pixels (the calibration removes it)
  (void)d;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_fig3_1_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
