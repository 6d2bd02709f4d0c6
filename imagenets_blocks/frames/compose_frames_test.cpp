#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(ComposeFrames, ChainsHandComputedFrames) {
  BlockHarness h("imagenets/ComposeFrames");
  // robot -> camera: 1 m along x, turned 90 deg about z; camera -> marker: 2 m along camera y.
  h.input("a", frame(isometry(1, 0, 0, M_PI / 2), "robot", "camera"));
  h.input("b", frame(isometry(0, 2, 0), "camera", "marker"));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "robot");
  EXPECT_EQ(out->child_frame_id, "marker");
  EXPECT_NEAR(out->transform.translation.x, -1, 1e-12);  // camera y is robot -x
  EXPECT_NEAR(out->transform.translation.y, 0, 1e-12);
  EXPECT_NEAR(out->transform.rotation.z, std::sqrt(0.5), 1e-12);
}

TEST(ComposeFrames, BadInputsAreNamedErrors) {
  BlockHarness h("imagenets/ComposeFrames");
  h.input("a", frame(isometry(1, 0, 0), "robot", "camera"));
  h.input("b", frame(isometry(0, 2, 0), "hand", "marker"));
  EXPECT_NE(h.runError().find("input 'a' ends in 'camera' but input 'b' starts in 'hand'"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("frame"));
  h.set("check_frames", false);
  EXPECT_EQ(h.runError(), "");

  auto nan = frame(isometry(0, 2, 0), "camera", "marker");
  nan->transform.translation.z = std::nan("");
  h.input("b", nan);
  EXPECT_NE(h.runError().find("input 'b' translation: z is nan"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("frame"));

  auto scaled = frame(isometry(0, 2, 0), "camera", "marker");
  scaled->transform.rotation.w = 0.5;
  h.input("b", scaled);
  EXPECT_NE(h.runError().find("input 'b': quaternion"), std::string::npos) << h.runError();
  h.clear("b");
  EXPECT_EQ(h.runError(), "input 'b' has no value");
}
