// rostest: the simulator runs the mobile manipulator (robot_description/config/mobile_manipulator:
// a URDF written for it, 7-joint arm, pan-tilt head with a stereo pair and a mono RGB camera)
// through the standard interfaces only: its arm and head move through their
// FollowJointTrajectory controllers and /joint_states follows; /robot_description is its URDF,
// which robot_state_publisher turns into TF; each head camera (the stereo pair and the mono one)
// publishes image + camera_info in which the gripper's target appears where the TRUE geometry
// (TF of the true robot) projects it; and the true robot differs from the URDF by its own errors.
#include <cmath>
#include <cstdio>
#include <tuple>

#include <actionlib/client/simple_action_client.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Trigger.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_listener.h>
#include <urdf/model.h>

#include "imagenets/calling_thread_queue.h"
#include "imagenets/package_file.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets/vision/marker.h"
#include "robot_description/robot_model.h"

namespace {

using Trajectory = actionlib::SimpleActionClient<control_msgs::FollowJointTrajectoryAction>;

std::string descriptionPath() {
  return ros::NodeHandle("~").param<std::string>(
      "description", imagenets::packageFile("robot_description", "config/mobile_manipulator/robot.yaml"));
}

class FriendSimMobileManipulator : public ::testing::Test {
 protected:
  // The calibration pose (the target faces the head), through the controllers only.
  static void SetUpTestSuite() {
    const auto d = robot_description::loadRobotDescription(descriptionPath());
    imagenets::CallingThreadQueue clients;  // called back only in its waitUntil
    Trajectory arm(clients.nodeHandle(), "arm_controller/follow_joint_trajectory", false),
        head(clients.nodeHandle(), "head_controller/follow_joint_trajectory", false);
    ASSERT_TRUE(clients.waitUntil([&] { return arm.isServerConnected() && head.isServerConnected(); }, 30));
    for (auto [client, chain, q] : {std::make_tuple(&arm, &d.arm, &d.arm_calibration_pose),
                                    std::make_tuple(&head, &d.head, &d.head_calibration_pose)}) {
      control_msgs::FollowJointTrajectoryGoal g;
      g.trajectory.joint_names = chain->names();
      trajectory_msgs::JointTrajectoryPoint p;
      p.positions = *q;
      p.time_from_start = ros::Duration(4.0);
      g.trajectory.points.push_back(p);
      client->sendGoal(g);
    }
    ASSERT_TRUE(clients.waitUntil([&] { return arm.getState().isDone() && head.getState().isDone(); }, 60));
    ASSERT_EQ(arm.getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << arm.getState().getText();
    ASSERT_EQ(head.getState(), actionlib::SimpleClientGoalState::SUCCEEDED) << head.getState().getText();
  }

  robot_description::RobotModel nominal_{robot_description::loadRobotDescription(descriptionPath())};
};

TEST_F(FriendSimMobileManipulator, JointStatesReportTheCalibrationPoseOfAllNineJoints) {
  LatestMessage<sensor_msgs::JointState> states("joint_states");
  const auto m = states.waitFrom(ros::Time::now(), 10);
  ASSERT_TRUE(m) << "no /joint_states";
  const auto& d = nominal_.description();
  std::vector<std::string> names = d.arm.names();
  std::vector<double> want = d.arm_calibration_pose;
  for (const auto& n : d.head.names()) names.push_back(n);
  want.insert(want.end(), d.head_calibration_pose.begin(), d.head_calibration_pose.end());
  ASSERT_EQ(names.size(), 9u);
  for (size_t i = 0; i < names.size(); ++i) {
    const auto it = std::find(m->name.begin(), m->name.end(), names[i]);
    ASSERT_NE(it, m->name.end()) << names[i] << " missing from /joint_states";
    EXPECT_NEAR(m->position[it - m->name.begin()], want[i], 0.01) << names[i];
  }
}

TEST_F(FriendSimMobileManipulator, TheUrdfOnRobotDescriptionIsTheTrueRobotsAndDrivesTf) {
  std::string xml;
  ASSERT_TRUE(ros::param::get("/robot_description", xml)) << "/robot_description is not set";
  urdf::Model model;
  ASSERT_TRUE(model.initString(xml)) << "/robot_description does not parse";
  EXPECT_EQ(model.getName(), "mobile_manipulator");
  for (const char* link : {"head_camera_rgb_optical_frame", "stereo_left_optical_frame", "target_mount_link"}) {
    EXPECT_TRUE(model.getLink(link)) << link;
  }
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  // The true head mount is off the drawing by its true error (12.2 mm): TF shows the true robot.
  const auto tf = buffer.lookupTransform("base_link", "head_mount_link", ros::Time(0), ros::Duration(10));
  const double off = (tf2::transformToEigen(tf).translation() - nominal_.headBase().translation()).norm();
  std::printf("true head mount %.2f mm from the URDF's\n", 1000 * off);
  EXPECT_NEAR(off, 0.0122, 0.0005);
}

TEST_F(FriendSimMobileManipulator, EachHeadCameraShowsTheTargetWhereTheTrueGeometryProjectsIt) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const auto marker = imagenets::marker::MarkerDescription::load(
      imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml"));
  LatestMessage<sensor_msgs::Image> left("stereo/left/image_raw"), right("stereo/right/image_raw"),
      mono("head_camera/image_raw");
  LatestMessage<sensor_msgs::CameraInfo> left_info("stereo/left/camera_info"), right_info("stereo/right/camera_info"),
      mono_info("head_camera/camera_info");
  ros::Duration(1.0).sleep();  // subscriptions connected
  int checked = 0;
  for (auto [trigger, image, info] : {std::make_tuple("stereo/trigger", &left, &left_info),
                                      std::make_tuple("stereo/trigger", &right, &right_info),
                                      std::make_tuple("head_camera/trigger", &mono, &mono_info)}) {
    const ros::Time before = ros::Time::now() - ros::Duration(0.001);
    std_srvs::Trigger t;
    ASSERT_TRUE(ros::service::waitForService(trigger, 10000) && ros::service::call(trigger, t)) << trigger;
    ASSERT_TRUE(t.response.success) << t.response.message;
    const auto img = image->waitFrom(before, 5);
    ASSERT_TRUE(img) << "no image after " << trigger;
    const auto ci = info->waitFrom(img->header.stamp, 5);
    ASSERT_TRUE(ci) << "no camera_info beside " << img->header.frame_id;
    EXPECT_EQ(ci->header.frame_id, img->header.frame_id);
    EXPECT_EQ(img->width, ci->width);
    // The true geometry from TF (robot_state_publisher on the true robot's URDF).
    const Eigen::Isometry3d marker_in_cam = tf2::transformToEigen(buffer.lookupTransform(
        img->header.frame_id, "target_mount_link", img->header.stamp, ros::Duration(5)));
    std::vector<cv::Point3d> obj;
    for (const auto& c : marker.definedPoints()) {
      const Eigen::Vector3d p = marker_in_cam * Eigen::Vector3d(c.x, c.y, c.z);
      obj.emplace_back(p.x(), p.y(), p.z());
    }
    cv::Mat K(3, 3, CV_64F, const_cast<double*>(ci->K.data())), D(ci->D);
    std::vector<cv::Point2d> expected;
    cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, expected);
    ASSERT_EQ(img->encoding, "mono8");
    const cv::Mat gray(img->height, img->width, CV_8U, const_cast<uint8_t*>(img->data.data()), img->step);
    cv::Mat binary;
    cv::threshold(gray, binary, 60, 255, cv::THRESH_BINARY);
    const auto det = imagenets::marker::detect(gray, binary, imagenets::render::CameraModel::fromCameraInfo(*ci), marker);
    ASSERT_TRUE(det.found) << "target not detected in " << img->header.frame_id;
    double worst = 0;
    for (int i = 0; i < 8; ++i) worst = std::max(worst, cv::norm(det.points[i] - expected[i]));
    std::printf("%s (%ux%u): worst of the 8 points %.3f px from the true projection, %.0f mm away\n",
                img->header.frame_id.c_str(), img->width, img->height, worst, 1000 * marker_in_cam.translation().norm());
    EXPECT_LT(worst, 0.3) << img->header.frame_id;
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_mobile_manipulator_rostest");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
