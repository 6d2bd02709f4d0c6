#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include <algorithm>

#include "frame_test_util.h"
#include "robot_description/robot_model.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

namespace {

// Siciliano's three-link anthropomorphic arm (see frames_test.cpp), a2 = 0.4, a3 = 0.3.
const std::vector<double> kArm{0, 0, 0, M_PI / 2, 0, 0, 0.4, 0, 0, 0, 0.3, 0};

sensor_msgs::JointState::Ptr joints(std::vector<std::string> names, std::vector<double> positions) {
  sensor_msgs::JointState::Ptr js(new sensor_msgs::JointState);
  js->name = std::move(names);
  js->position = std::move(positions);
  return js;
}

}  // namespace

TEST(DhForwardKinematics, AnthropomorphicArmByJointName) {
  BlockHarness h("imagenets/DhForwardKinematics");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.set("dh_table", kArm).set("joint_names", "j1, j2, j3").set("base_frame", "arm_base").set("tip_frame", "tcp");
  const double q1 = 0.7, q2 = -0.4, q3 = 1.2;
  // Joint states arrive in any order, with extra joints.
  h.input("joints", joints({"gripper", "j3", "j1", "j2"}, {0.05, q3, q1, q2}));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "arm_base");
  EXPECT_EQ(out->child_frame_id, "tcp");
  const double r = 0.4 * std::cos(q2) + 0.3 * std::cos(q2 + q3);
  EXPECT_NEAR(out->transform.translation.x, std::cos(q1) * r, 1e-12);
  EXPECT_NEAR(out->transform.translation.y, std::sin(q1) * r, 1e-12);
  EXPECT_NEAR(out->transform.translation.z, 0.4 * std::sin(q2) + 0.3 * std::sin(q2 + q3), 1e-12);
  auto links = h.output<geometry_msgs::PoseArray>("links");
  ASSERT_TRUE(links);
  ASSERT_EQ(links->poses.size(), 3u);
  // Link 2 ends at the elbow: (c1 a2 c2, s1 a2 c2, a2 s2).
  EXPECT_NEAR(links->poses[1].position.z, 0.4 * std::sin(q2), 1e-12);
}

TEST(DhForwardKinematics, ToolOffsetAlongLastLinkX) {
  BlockHarness h("imagenets/DhForwardKinematics");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  // One joint, link 1 m along x; tool 0.1 m further along the link's x: at q = 90 deg the tip is at (0, 1.1, 0).
  h.set("dh_table", std::vector<double>{0, 0, 1, 0}).set("tool_offset", std::vector<double>{0.1, 0, 0, 0, 0, 0});
  h.input("joints", joints({}, {M_PI / 2}));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  EXPECT_NEAR(out->transform.translation.x, 0, 1e-12);
  EXPECT_NEAR(out->transform.translation.y, 1.1, 1e-12);
}

TEST(DhForwardKinematics, BadInputsAreNamedErrors) {
  BlockHarness h("imagenets/DhForwardKinematics");
  h.set("description", robot_description::exampleRobotDescriptionPath());
  h.input("joints", joints({}, {0.1, 0.2, 0.3}));
  EXPECT_NE(h.runError().find("property 'dh_table': a DH table needs 4 values per joint"), std::string::npos)
      << h.runError();
  h.set("dh_table", kArm);
  h.input("joints", joints({}, {0.1, 0.2}));
  EXPECT_NE(h.runError().find("2 positions, the DH table has 3 joints"), std::string::npos) << h.runError();
  h.input("joints", joints({}, {0.1, std::nan(""), 0.3}));
  EXPECT_NE(h.runError().find("input 'joints': forward kinematics of 'link_*': joint 'joint_2' position is not finite"),
            std::string::npos)
      << h.runError();
  h.set("joint_names", "j1,j2,j9");
  h.input("joints", joints({"j1", "j2", "j3"}, {0.1, 0.2, 0.3}));
  EXPECT_NE(h.runError().find("input 'joints': joint 'j9' is missing"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("frame"));
}

TEST(DhForwardKinematics, ReadsTheChainsFromTheRobotDescription) {
  // The description's arm to the marker and head to the left camera equal the robot model's.
  const auto d = robot_description::loadRobotDescription(robot_description::exampleRobotDescriptionPath());
  const robot_description::RobotModel model(d);
  BlockHarness arm("imagenets/DhForwardKinematics");
  arm.set("description", robot_description::exampleRobotDescriptionPath());
  arm.set("chain", std::string("arm")).set("description", std::string(robot_description::exampleRobotDescriptionPath()))
      .set("tip", std::string("marker"));
  // Joint states by name, in reverse order: the description's names pick them.
  std::vector<std::string> names = d.arm.names();
  std::vector<double> q = d.arm_calibration_pose;
  std::reverse(names.begin(), names.end());
  std::reverse(q.begin(), q.end());
  arm.input("joints", joints(names, q));
  arm.run();
  const auto marker = arm.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(marker);
  const Eigen::Vector3d expected = model.marker(d.arm_calibration_pose).translation();
  EXPECT_NEAR(marker->transform.translation.x, expected.x(), 1e-12);
  EXPECT_NEAR(marker->transform.translation.y, expected.y(), 1e-12);
  EXPECT_NEAR(marker->transform.translation.z, expected.z(), 1e-12);

  BlockHarness head("imagenets/DhForwardKinematics");

  head.set("description", robot_description::exampleRobotDescriptionPath());
  head.set("chain", std::string("head")).set("tip", std::string("right_camera")).set("from", std::string("link_0"));
  head.input("joints", joints(d.head.names(), d.head_calibration_pose));
  head.run();
  const auto camera = head.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(camera);
  const Eigen::Vector3d cam = (d.head.mount.inverse() * model.rightCamera(d.head_calibration_pose)).translation();
  EXPECT_NEAR(camera->transform.translation.x, cam.x(), 1e-12);
  EXPECT_NEAR(camera->transform.translation.z, cam.z(), 1e-12);

  head.set("tip", std::string("marker"));
  EXPECT_NE(head.runError().find("property 'tip': 'marker' is not on the head chain"), std::string::npos)
      << head.runError();
  head.set("tip", std::string("last_link")).set("description", std::string("/nonexistent/robot.yaml"));
  EXPECT_NE(head.runError().find("property 'description': robot description '/nonexistent/robot.yaml'"),
            std::string::npos)
      << head.runError();
}
