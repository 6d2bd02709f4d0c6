// rostest: hardware blocks reach the (simulated) robot through ROS; the Fig. 3.1 net leaves the
// TCP near the stereo image centre of the TRUE cameras.
#include <cmath>
#include <cstdio>
#include <mutex>

#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <ros/package.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <tf2_eigen/tf2_eigen.h>

#include "imagenets/executor.h"
#include "imagenets/blocks/block_harness.h"
#include "imagenets/registry.h"

using namespace imagenets;

namespace {

std::string netPath(const std::string& name) { return ros::package::getPath("friend_calibration") + "/config/nets/" + name; }

std::unique_ptr<Executor> netFromText(const std::string& yaml) {
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "<test>", "")), ExecutorOptions{2});
}

template <class M>
boost::shared_ptr<const M> nextMessage(const std::string& topic) {
  return ros::topic::waitForMessage<M>(topic, ros::Duration(30));
}

std::string failures(const RunReport& r) {
  std::string s;
  for (const auto& f : r.failed) s += f + "\n";
  for (const auto& f : r.not_run) s += "not run: " + f + "\n";
  return s;
}

TEST(FriendSimBlocks, Fig31NetLeavesTheTcpNearTheStereoImageCentre) {
  Executor exec(Net::loadFile(netPath("fig3_1_look_at_tcp.yaml")), ExecutorOptions{2});
  const RunReport report = exec.run();
  ASSERT_TRUE(report.ok()) << failures(report);
  ros::Duration(0.2).sleep();
  // Where the TCP really is, seen by the real cameras (ground truth: tests may read it).
  const auto tcp = nextMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/tcp");
  const auto left = nextMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/left_camera");
  const auto right = nextMessage<geometry_msgs::TransformStamped>("friend_sim/ground_truth/right_camera");
  ASSERT_TRUE(tcp && left && right) << "ground truth missing";
  // Ideal pinhole projection with the cameras' rectified intrinsics (fx = 1400, centre 512, 384).
  std::vector<cv::Point2d> px;
  for (const auto& cam : {left, right}) {
    const Eigen::Vector3d p = tf2::transformToEigen(*cam).inverse() * tf2::transformToEigen(*tcp).translation();
    ASSERT_GT(p.z(), 0.2);
    px.emplace_back(1400.0 * p.x() / p.z() + 512, 1400.0 * p.y() / p.z() + 384);
  }
  const cv::Point2d mid = (px[0] + px[1]) / 2;
  const double off = cv::norm(mid - cv::Point2d(512, 384));
  std::printf("TCP after Fig. 3.1: left (%.1f, %.1f) right (%.1f, %.1f) px; stereo midpoint %.1f px from the centre\n",
              px[0].x, px[0].y, px[1].x, px[1].y, off);
  // Nominal kinematics against a head mounted ~2 deg off (2 deg = 49 px at fx = 1400): tens of
  // pixels, not hundreds. Removing this residual is the calibration's job.
  EXPECT_LT(off, 100.0);
  for (const auto& p : px) {
    EXPECT_GT(p.x, 0);
    EXPECT_LT(p.x, 1024);
    EXPECT_GT(p.y, 0);
    EXPECT_LT(p.y, 768);
  }
  // The net's own output: the head moved where LookAtTcp asked.
  const auto reached = exec.output<sensor_msgs::JointState>("move_head.reached");
  const auto asked = exec.output<sensor_msgs::JointState>("look_at_tcp.head_configuration");
  ASSERT_TRUE(reached && asked);
  EXPECT_NEAR(reached->position[0], asked->position[0], 1e-9);
  EXPECT_NEAR(reached->position[1], asked->position[1], 1e-9);
}

TEST(FriendSimBlocks, GrabStereoPairGivesASynchronisedPairAfterSettling) {
  auto exec = netFromText(R"(
blocks:
  grab: {type: imagenets/GrabStereoPair, properties: {timeout: 10}}
)");
  const RunReport report = exec->run();
  ASSERT_TRUE(report.ok()) << failures(report);
  const auto l = exec->output<sensor_msgs::Image>("grab.left_image");
  const auto r = exec->output<sensor_msgs::Image>("grab.right_image");
  const auto li = exec->output<sensor_msgs::CameraInfo>("grab.left_info");
  const auto ri = exec->output<sensor_msgs::CameraInfo>("grab.right_info");
  ASSERT_TRUE(l && r && li && ri);
  EXPECT_EQ(l->header.stamp, r->header.stamp);
  EXPECT_EQ(li->header.stamp, l->header.stamp);
  EXPECT_EQ(ri->header.stamp, r->header.stamp);
  EXPECT_EQ(l->width, 1024u);
  EXPECT_EQ(r->header.frame_id, "stereo_right_optical_frame");
}

TEST(FriendSimBlocks, GrabImageGivesOneCamerasImageAfterSettling) {
  auto exec = netFromText(R"(
blocks:
  grab: {type: imagenets/GrabImage, properties: {camera: hand_camera, timeout: 10}}
)");
  const RunReport report = exec->run();
  ASSERT_TRUE(report.ok()) << failures(report);
  const auto image = exec->output<sensor_msgs::Image>("grab.image");
  const auto info = exec->output<sensor_msgs::CameraInfo>("grab.camera_info");
  ASSERT_TRUE(image && info);
  EXPECT_EQ(info->header.stamp, image->header.stamp);
  EXPECT_EQ(image->width, info->width);
  EXPECT_EQ(info->header.frame_id, image->header.frame_id);
  EXPECT_FALSE(image->header.frame_id.empty());
  // A camera that does not exist is named.
  auto silent = netFromText(R"(
blocks:
  grab: {type: imagenets/GrabImage, properties: {camera: no_such_camera, timeout: 1}}
)");
  const RunReport failed = silent->run();
  ASSERT_FALSE(failed.ok());
  EXPECT_NE(failures(failed).find("no publisher on '/no_such_camera/image_raw'"), std::string::npos) << failures(failed);
}

TEST(FriendSimBlocks, SensorsAndWorldModel) {
  auto exec = netFromText(R"(
blocks:
  joints: {type: imagenets/ReadJointStates}
  ft: {type: imagenets/ReadForceTorque}
  robot: {type: imagenets/CreateRobotConfiguration,
          properties: {group: head, angles: [5, 30], description: $(find friend_description)/config/robot.yaml}}
  head: {type: imagenets/MoveHead}
  arm_now: {type: imagenets/ReadJointStates}
links:
  - robot.configuration -> head.configuration
  - head.reached -> arm_now.after
)");
  const RunReport report = exec->run();
  ASSERT_TRUE(report.ok()) << failures(report);
  const auto js = exec->output<sensor_msgs::JointState>("arm_now.joint_states");
  ASSERT_TRUE(js);
  ASSERT_EQ(js->name.size(), 9u);
  EXPECT_NEAR(js->position[7], 5 * M_PI / 180, 1e-6);  // head_pan_joint, no encoder noise here
  const auto ft = exec->output<geometry_msgs::WrenchStamped>("ft.wrench");
  ASSERT_TRUE(ft);
  const double f = std::sqrt(ft->wrench.force.x * ft->wrench.force.x + ft->wrench.force.y * ft->wrench.force.y +
                             ft->wrench.force.z * ft->wrench.force.z);
  EXPECT_NEAR(f, 0.8 * 9.81, 0.4) << "payload gravity";

  // World model round trip.
  auto wm = netFromText(R"(
blocks:
  get: {type: imagenets/WorldModelGet, properties: {name: cup}}
)");
  imagenets::blocks::BlockHarness set("imagenets/WorldModelSet");
  auto pose = boost::make_shared<geometry_msgs::PoseStamped>();
  pose->pose.position.x = 0.7;
  pose->pose.position.z = 0.8;
  pose->pose.orientation.w = 1.0;
  set.set("name", std::string("cup")).input("pose", pose).run();
  ASSERT_TRUE(wm->run().ok());
  const auto got = wm->output<geometry_msgs::PoseStamped>("get.pose");
  ASSERT_TRUE(got);
  EXPECT_DOUBLE_EQ(got->pose.position.x, 0.7);
  EXPECT_EQ(got->header.frame_id, "base_link");
  wm->setPropertyText("get", "name", "no_such_object");
  const RunReport missing = wm->run();
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.failed[0].find("no_such_object"), std::string::npos) << missing.failed[0];
}

TEST(FriendSimBlocks, MissingServerAndRejectedGoalAreClearErrors) {
  auto exec = netFromText(R"(
blocks:
  robot: {type: imagenets/CreateRobotConfiguration, properties: {description: $(find friend_description)/config/robot.yaml}}
  arm: {type: imagenets/MoveArm, properties: {action: no_such/move_joints, server_timeout: 0.5}}
links:
  - robot.configuration -> arm.configuration
)");
  RunReport report = exec->run();
  ASSERT_EQ(report.failed.size(), 1u);
  EXPECT_NE(report.failed[0].find("no_such/move_joints"), std::string::npos) << report.failed[0];
  EXPECT_NE(report.failed[0].find("not available"), std::string::npos) << report.failed[0];

  // A goal the server rejects: joint 1 at 169 deg is inside the property's check only if the
  // description allows it; send an explicit out-of-limit state instead.
  imagenets::blocks::BlockHarness arm("imagenets/MoveArm");
  auto target = boost::make_shared<sensor_msgs::JointState>();
  target->name = {"arm_joint_2"};
  target->position = {3.0};
  const std::string error = arm.input("configuration", target).runError();
  EXPECT_NE(error.find("REJECTED"), std::string::npos) << error;
  EXPECT_NE(error.find("arm_joint_2"), std::string::npos) << error;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "friend_sim_blocks_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
