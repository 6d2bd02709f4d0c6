#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(InvertFrame, InvertsAndSwapsFrameIds) {
  BlockHarness h("imagenets/InvertFrame");
  // camera -> marker: 2 m ahead (z), turned 180 deg about x. Inverse: marker -> camera at
  // R^T * -(0,0,2) = (0,0,2) (flipping z twice), same rotation.
  h.input("frame", frame(isometry(0, 0, 2, M_PI, Eigen::Vector3d::UnitX()), "camera", "marker"));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "marker");
  EXPECT_EQ(out->child_frame_id, "camera");
  EXPECT_NEAR(out->transform.translation.z, 2, 1e-12);
  EXPECT_NEAR(std::abs(out->transform.rotation.x), 1, 1e-12);
  // Inverse of the inverse is the original.
  BlockHarness twice("imagenets/InvertFrame");
  twice.input("frame", out);
  twice.run();
  EXPECT_TRUE(toEigen(*twice.output<geometry_msgs::TransformStamped>("frame"))
                  .isApprox(isometry(0, 0, 2, M_PI, Eigen::Vector3d::UnitX())));
}

TEST(InvertFrame, RejectsNonUnitQuaternion) {
  BlockHarness h("imagenets/InvertFrame");
  auto bad = frame(isometry(0, 0, 2), "camera", "marker");
  bad->transform.rotation.w = 0;  // all-zero quaternion
  EXPECT_NE(h.input("frame", bad).runError().find("has norm 0"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("frame"));
}
