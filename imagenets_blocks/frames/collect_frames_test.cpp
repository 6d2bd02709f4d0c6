#include <geometry_msgs/PoseArray.h>
#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(CollectFrames, GathersPresentFramesInOrder) {
  BlockHarness h("imagenets/CollectFrames");
  h.set("inputs", 3);
  h.input("frame_1", frame(isometry(1, 0, 0), "robot", "m"));
  h.input("frame_3", frame(isometry(3, 0, 0), "robot", "m"));
  h.run();
  auto out = h.output<geometry_msgs::PoseArray>("poses");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "robot");
  ASSERT_EQ(out->poses.size(), 2u);
  EXPECT_DOUBLE_EQ(out->poses[1].position.x, 3);
  h.input("frame_2", frame(isometry(2, 0, 0), "camera", "m"));
  EXPECT_NE(h.runError().find("input 'frame_2' is in frame 'camera', input 'frame_1' in 'robot'"), std::string::npos);
  h.clear("frame_1").clear("frame_2").clear("frame_3");
  EXPECT_NE(h.runError().find("no input frame present"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("poses"));
}
