#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(SplitAndBuildFrame, SplitThenBuildGivesTheFrameBack) {
  const Eigen::Isometry3d t = isometry(0.1, -0.2, 0.3, 0.8, Eigen::Vector3d(1, 1, 0));
  BlockHarness split("imagenets/SplitFrame");
  split.input("frame", frame(t, "base", "hand"));
  split.run();
  auto translation = split.output<geometry_msgs::Vector3Stamped>("translation");
  auto rotation = split.output<geometry_msgs::QuaternionStamped>("rotation");
  ASSERT_TRUE(translation && rotation);
  EXPECT_DOUBLE_EQ(translation->vector.y, -0.2);
  // 0.8 rad about (1,1,0)/sqrt2: w = cos 0.4, x = y = sin 0.4 / sqrt 2.
  EXPECT_NEAR(rotation->quaternion.w, std::cos(0.4), 1e-12);
  EXPECT_NEAR(rotation->quaternion.x, std::sin(0.4) / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(rotation->header.frame_id, "base");

  BlockHarness build("imagenets/BuildFrame");
  build.set("child_frame_id", "hand");
  build.input("translation", translation).input("rotation", rotation);
  build.run();
  auto out = build.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "base");
  EXPECT_EQ(out->child_frame_id, "hand");
  EXPECT_TRUE(toEigen(*out).isApprox(t, 1e-12));
}
