#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>
#include <sensor_msgs/JointState.h>

#include "frame_test_util.h"

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
  h.input("joints", joints({}, {0.1, 0.2, 0.3}));
  EXPECT_NE(h.runError().find("property 'dh_table': DH table has 0 values"), std::string::npos) << h.runError();
  h.set("dh_table", kArm);
  h.input("joints", joints({}, {0.1, 0.2}));
  EXPECT_NE(h.runError().find("2 positions, the DH table has 3 joints"), std::string::npos) << h.runError();
  h.input("joints", joints({}, {0.1, std::nan(""), 0.3}));
  EXPECT_NE(h.runError().find("joint 2 value is nan"), std::string::npos) << h.runError();
  h.set("joint_names", "j1,j2,j9");
  h.input("joints", joints({"j1", "j2", "j3"}, {0.1, 0.2, 0.3}));
  EXPECT_NE(h.runError().find("no joint named 'j9'"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("frame"));
}
