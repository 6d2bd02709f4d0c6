#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(StaticFrame, CameraOpticalFrameFromRollPitchYaw) {
  // The REP-103 optical frame of a camera looking along base x: rpy (-pi/2, 0, -pi/2) maps
  // optical z (forward) to base x, optical x (right) to base -y, optical y (down) to base -z.
  BlockHarness h("imagenets/StaticFrame");
  h.set("frame_id", "base_link").set("child_frame_id", "camera_optical");
  h.set("xyz", std::vector<double>{0.1, 0, 1.2}).set("rpy", std::vector<double>{-M_PI / 2, 0, -M_PI / 2});
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->child_frame_id, "camera_optical");
  const Eigen::Isometry3d t = toEigen(*out);
  EXPECT_NEAR((t.linear() * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitX()).norm(), 0, 1e-12);
  EXPECT_NEAR((t.linear() * Eigen::Vector3d::UnitX() + Eigen::Vector3d::UnitY()).norm(), 0, 1e-12);
  EXPECT_NEAR((t.linear() * Eigen::Vector3d::UnitY() + Eigen::Vector3d::UnitZ()).norm(), 0, 1e-12);
  EXPECT_DOUBLE_EQ(out->transform.translation.z, 1.2);
  h.set("xyz", std::vector<double>{0, 0});
  EXPECT_NE(h.runError().find("property 'xyz': 2 values, expected 3"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("frame"));
}
