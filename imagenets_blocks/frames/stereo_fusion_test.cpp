#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(StereoFusion, MeanWhenBothAgree) {
  BlockHarness h("imagenets/StereoFusion");
  h.input("first", frame(isometry(0.100, 0.2, 1.0, 0.30), "left_camera", "marker"));
  h.input("second", frame(isometry(0.106, 0.2, 1.0, 0.34), "left_camera", "marker"));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->child_frame_id, "marker");
  EXPECT_NEAR(out->transform.translation.x, 0.103, 1e-12);
  EXPECT_NEAR(out->transform.rotation.z, std::sin(0.16), 1e-9);
}

TEST(StereoFusion, TheValidOneWhenOnlyOneIsPresent) {
  BlockHarness h("imagenets/StereoFusion");
  h.input("second", frame(isometry(0.5, 0, 1), "left_camera", "marker"));
  h.run();
  EXPECT_DOUBLE_EQ(h.output<geometry_msgs::TransformStamped>("frame")->transform.translation.x, 0.5);
}

TEST(StereoFusion, DisagreementIsInvalidWithReason) {
  BlockHarness h("imagenets/StereoFusion");
  h.set("max_position_difference", 0.005);
  h.input("first", frame(isometry(0.100, 0.2, 1.0), "left_camera", "marker"));
  h.input("second", frame(isometry(0.110, 0.2, 1.0), "left_camera", "marker"));
  EXPECT_NE(h.runError().find("no fused frame: poses disagree: positions 0.01 m apart (limit 0.005 m)"),
            std::string::npos)
      << h.runError();
  EXPECT_FALSE(h.hasOutput("frame"));
  h.set("max_position_difference", 0.02).set("max_angle_difference", 0.05);
  h.input("second", frame(isometry(0.100, 0.2, 1.0, 0.1), "left_camera", "marker"));
  EXPECT_NE(h.runError().find("rotations 0.1 rad apart"), std::string::npos) << h.runError();
  h.clear("first").clear("second");
  EXPECT_NE(h.runError().find("neither pose is valid"), std::string::npos);
  h.input("first", frame(isometry(0, 0, 1), "left_camera", "marker"));
  h.input("second", frame(isometry(0, 0, 1), "right_camera", "marker"));
  EXPECT_NE(h.runError().find("are not the same frame"), std::string::npos);
}
