// rostest: the simulator's cameras show the gripper marker where the TRUE geometry projects it
// (sub-pixel, found by the project's marker detector), stereo pairs carry identical stamps with camera_info beside them, ground truth
// agrees with the TF tree of the true robot, and camera faults do what they say.
#include <cmath>
#include <cstdio>
#include <mutex>

#include <actionlib/client/simple_action_client.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/transform_listener.h>

#include "robot_description/robot_model.h"
#include "robot_description/urdf_writer.h"
#include "imagenets/vision/marker.h"
#include "friend_msgs/MoveJointsAction.h"
#include "imagenets/calling_thread_queue.h"
#include "imagenets/testing/rostest_util.h"
#include "imagenets/package_file.h"

namespace {

using Client = actionlib::SimpleActionClient<friend_msgs::MoveJointsAction>;

Eigen::Isometry3d toEigen(const geometry_msgs::TransformStamped& t) { return tf2::transformToEigen(t); }

cv::Mat toMat(const sensor_msgs::Image& img) {
  EXPECT_EQ(img.encoding, "mono8");
  return cv::Mat(img.height, img.width, CV_8U, const_cast<uint8_t*>(img.data.data()), img.step).clone();
}

class FriendSimCameras : public ::testing::Test {
 protected:
  // The robot the simulator runs (~description, as friend_sim.launch's `description`; FRIEND's by
  // default): friend_sim_six_axis.test runs these tests on a robot that exists only as a URDF.
  static std::string descriptionPath() {
    return ros::NodeHandle("~").param<std::string>("description", imagenets::packageFile("friend_description", "config/robot.yaml"));
  }
  static void SetUpTestSuite() {
    // Calibration pose of the description: the marker faces the stereo camera.
    const auto d = robot_description::loadRobotDescription(descriptionPath());
    imagenets::CallingThreadQueue clients;  // called back only in its waitUntil (it says why)
    Client arm(clients.nodeHandle(), "arm/move_joints", false), head(clients.nodeHandle(), "head/move_joints", false);
    ASSERT_TRUE(clients.waitUntil([&] { return arm.isServerConnected() && head.isServerConnected(); }, 15));
    friend_msgs::MoveJointsGoal ga, gh;
    ga.positions = d.arm_calibration_pose;
    gh.positions = d.head_calibration_pose;
    arm.sendGoal(ga);
    head.sendGoal(gh);
    ASSERT_TRUE(clients.waitUntil([&] { return arm.getState().isDone() && head.getState().isDone(); }, 40));
    ASSERT_EQ(arm.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
    ASSERT_EQ(head.getState(), actionlib::SimpleClientGoalState::SUCCEEDED);
  }

  // Triggers a pair and waits for both images (newer than before the trigger).
  bool grab(sensor_msgs::ImageConstPtr* l, sensor_msgs::ImageConstPtr* r, double timeout = 5.0) {
    const ros::Time before = ros::Time::now();
    std_srvs::Trigger t;
    if (!ros::service::waitForService("stereo/trigger", 10000) || !ros::service::call("stereo/trigger", t)) return false;
    // The service returns after publishing; the images are on their way.
    *l = left_.waitFrom(before - ros::Duration(0.001), timeout);
    *r = right_.waitFrom(before - ros::Duration(0.001), timeout);
    return *l && *r;
  }

  LatestMessage<sensor_msgs::Image> left_{"stereo/left/image_raw"}, right_{"stereo/right/image_raw"};
  LatestMessage<sensor_msgs::CameraInfo> left_info_{"stereo/left/camera_info"}, right_info_{"stereo/right/camera_info"};
  LatestMessage<geometry_msgs::TransformStamped> gt_marker_{"friend_sim/ground_truth/marker"},
      gt_left_{"friend_sim/ground_truth/left_camera"}, gt_right_{"friend_sim/ground_truth/right_camera"};
};

TEST_F(FriendSimCameras, MarkerAppearsWhereTheTrueGeometryProjectsIt) {
  ros::Duration(0.5).sleep();  // subscriptions connected
  sensor_msgs::ImageConstPtr l, r;
  ASSERT_TRUE(grab(&l, &r)) << "no stereo pair after stereo/trigger";
  EXPECT_EQ(l->header.stamp, r->header.stamp) << "left and right stamps differ";
  EXPECT_EQ(l->header.frame_id, "stereo_left_optical_frame");
  EXPECT_EQ(r->header.frame_id, "stereo_right_optical_frame");
  EXPECT_EQ(l->width, 1024u);
  EXPECT_EQ(l->height, 768u);
  auto li = left_info_.waitFrom(l->header.stamp - ros::Duration(1e-6), 2);
  auto ri = right_info_.waitFrom(r->header.stamp - ros::Duration(1e-6), 2);
  ASSERT_TRUE(li && ri) << "camera_info missing beside the images";
  EXPECT_EQ(li->header.stamp, l->header.stamp);

  auto gm = gt_marker_.wait(2), gl = gt_left_.wait(2),
       gr = gt_right_.wait(2);
  ASSERT_TRUE(gm && gl && gr) << "ground truth topics missing";
  // The project's marker detector (imagenets/vision/marker.h) on each image, compared with the
  // 8 defined points of the gripper marker projected through the TRUE geometry.
  const auto marker = imagenets::marker::MarkerDescription::load(ros::package::getPath("imagenets_vision") +
                                                                 "/config/markers/gripper.yaml");
  int checked = 0;
  for (auto [img, info, cam] : {std::make_tuple(l, li, gl), std::make_tuple(r, ri, gr)}) {
    const Eigen::Isometry3d marker_in_cam = toEigen(*cam).inverse() * toEigen(*gm);
    std::vector<cv::Point3d> obj;
    for (const auto& c : marker.definedPoints()) {
      const Eigen::Vector3d p = marker_in_cam * Eigen::Vector3d(c.x, c.y, c.z);
      obj.emplace_back(p.x(), p.y(), p.z());
    }
    cv::Mat K(3, 3, CV_64F, const_cast<double*>(info->K.data())), D(info->D);
    std::vector<cv::Point2d> expected;
    cv::projectPoints(obj, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, expected);
    const cv::Mat gray = toMat(*img);
    cv::Mat binary;
    cv::threshold(gray, binary, 60, 255, cv::THRESH_BINARY);
    const auto camera = imagenets::render::CameraModel::fromCameraInfo(*info);
    const auto det = imagenets::marker::detect(gray, binary, camera, marker);
    ASSERT_TRUE(det.found) << "marker not detected in " << img->header.frame_id << " (confidence " << det.confidence << ")";
    double worst = 0;
    for (int i = 0; i < 8; ++i) worst = std::max(worst, cv::norm(det.points[i] - expected[i]));
    const double position_error = (det.pose.translation() - marker_in_cam.translation()).norm();
    std::printf("%s: worst of the 8 points %.3f px from the true projection; pose %.2f mm, %.2f deg off\n",
                img->header.frame_id.c_str(), worst, position_error * 1000,
                imagenets::marker::rotationAngle(det.pose, marker_in_cam) * 180 / M_PI);
    EXPECT_LT(worst, 0.3) << img->header.frame_id << ": detected points differ from the true projection by " << worst << " px";
    ++checked;
  }
  EXPECT_EQ(checked, 2);
}

TEST_F(FriendSimCameras, GroundTruthAgreesWithTheTrueRobotTf) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ros::Duration(1.0).sleep();
  for (auto* topic : {&gt_left_, &gt_right_, &gt_marker_}) {
    auto gt = topic->wait(2);
    ASSERT_TRUE(gt);
    geometry_msgs::TransformStamped tf;
    try {
      tf = buffer.lookupTransform(gt->header.frame_id, gt->child_frame_id, gt->header.stamp, ros::Duration(2.0));
    } catch (const tf2::TransformException& e) {
      FAIL() << e.what();
    }
    const Eigen::Isometry3d a = toEigen(*gt), b = toEigen(tf);
    EXPECT_LT((a.translation() - b.translation()).norm(), 1e-6) << gt->child_frame_id;
    EXPECT_LT(Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle(), 1e-6) << gt->child_frame_id;
  }
  // And the truth is not the nominal robot: the head is mounted off by about 15 mm.
  const auto nominal = robot_description::RobotModel(robot_description::loadRobotDescription(descriptionPath()));
  // The head's link 0 as the robot's URDF names it (FRIEND: head_link_0, six_axis: head_mount).
  const auto head_link0 = robot_description::urdfChainMountJoint(nominal.description(), nominal.description().head).child;
  const auto tf = buffer.lookupTransform("base_link", head_link0, ros::Time(0));
  EXPECT_NEAR((toEigen(tf).translation() - nominal.headBase().translation()).norm(), 0.015, 0.002);
}

TEST_F(FriendSimCameras, DroppedFramesAndReflectionsFollowTheFaultParameters) {
  ros::NodeHandle sim("friend_sim");
  sim.setParam("faults/drop_frame_probability", 1.0);
  ros::Duration(0.3).sleep();
  sensor_msgs::ImageConstPtr l, r;
  EXPECT_FALSE(grab(&l, &r, 1.0)) << "frames published although every frame is dropped";
  sim.setParam("faults/drop_frame_probability", 0.0);
  ros::Duration(0.3).sleep();
  ASSERT_TRUE(grab(&l, &r));
  const cv::Mat clean = toMat(*l);
  sim.setParam("faults/reflection_probability", 1.0);
  ros::Duration(0.3).sleep();
  ASSERT_TRUE(grab(&l, &r));
  sim.setParam("faults/reflection_probability", 0.0);
  const cv::Mat glare = toMat(*l);
  // The highlight saturates pixels that are not saturated in the clean image.
  const int saturated_clean = cv::countNonZero(clean >= 250), saturated_glare = cv::countNonZero(glare >= 250);
  EXPECT_GT(saturated_glare, saturated_clean + 20);

  // A corrupted frame: a band of rows shifted sideways, so many rows differ from the clean image.
  sim.setParam("faults/corrupt_frame_probability", 1.0);
  ros::Duration(0.3).sleep();
  ASSERT_TRUE(grab(&l, &r));
  sim.setParam("faults/corrupt_frame_probability", 0.0);
  const cv::Mat corrupt = toMat(*l);
  int rows_changed = 0;
  for (int y = 0; y < clean.rows; ++y) {
    cv::Mat d;
    cv::absdiff(clean.row(y), corrupt.row(y), d);
    if (cv::mean(d)[0] > 20) ++rows_changed;
  }
  EXPECT_GT(rows_changed, clean.rows / 20);
  EXPECT_LT(rows_changed, clean.rows / 2);
}

// The camera goes silent while faults/camera_silent is true (a pulled cable), and comes back.
TEST_F(FriendSimCameras, SilentCameraPublishesNothingUntilTheFaultEnds) {
  ros::NodeHandle sim("friend_sim");
  auto trigger = [](std_srvs::Trigger* t) { return ros::service::call("stereo/trigger", *t); };
  sim.setParam("faults/camera_silent", true);
  std_srvs::Trigger t;
  // The simulator reads its parameters through a cache: wait until the change has reached it.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (trigger(&t) && t.response.success && ros::WallTime::now() < deadline) ros::WallDuration(0.05).sleep();
  ASSERT_FALSE(t.response.success) << "the trigger still succeeds with the camera silent";
  EXPECT_NE(t.response.message.find("silent"), std::string::npos) << t.response.message;
  sensor_msgs::ImageConstPtr l, r;
  EXPECT_FALSE(grab(&l, &r, 1.0)) << "images published although the camera is silent";
  sim.setParam("faults/camera_silent", false);
  bool back = false;
  for (int i = 0; i < 60 && !back; ++i) back = grab(&l, &r, 0.5);
  EXPECT_TRUE(back) << "no images after the camera_silent fault ended";
}

TEST_F(FriendSimCameras, IlluminationIsSettableLive) {
  ros::NodeHandle sim("friend_sim");
  sensor_msgs::ImageConstPtr l, r;
  ros::Duration(0.3).sleep();
  ASSERT_TRUE(grab(&l, &r));
  const double bright = cv::mean(toMat(*l))[0];
  sim.setParam("camera/illumination", 0.5);
  ros::Duration(0.3).sleep();
  ASSERT_TRUE(grab(&l, &r));
  sim.setParam("camera/illumination", 1.0);
  const double dim = cv::mean(toMat(*l))[0];
  EXPECT_NEAR(dim / bright, 0.5, 0.05) << "mean gray " << bright << " -> " << dim;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_cameras_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
