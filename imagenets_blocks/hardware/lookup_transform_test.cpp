#include <gtest/gtest.h>
#include <tf2_ros/buffer.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/ros_access.h"

using imagenets::BlockError;
using imagenets::blocks::BlockHarness;
namespace hardware = imagenets::blocks::hardware;

namespace {

geometry_msgs::TransformStamped edge(const std::string& parent, const std::string& child, double t, double x) {
  geometry_msgs::TransformStamped m;
  m.header.frame_id = parent;
  m.header.stamp = ros::Time(t);
  m.child_frame_id = child;
  m.transform.translation.x = x;
  m.transform.rotation.w = 1.0;
  return m;
}

// A buffer filled by hand (no ROS master needed): base_link -> pth_fixed_point (static) ->
// calibrated camera moving along x between t = 10 and t = 12.
tf2_ros::Buffer& filledBuffer() {
  static tf2_ros::Buffer buffer;
  static bool filled = false;
  if (!filled) {
    ros::Time::init();
    buffer.setUsingDedicatedThread(true);  // nothing else fills it: a timeout simply expires
    buffer.setTransform(edge("base_link", "pth_fixed_point", 0, 0.5), "test", true);
    buffer.setTransform(edge("pth_fixed_point", "calibrated/cam", 10, 0.0), "test");
    buffer.setTransform(edge("pth_fixed_point", "calibrated/cam", 12, 0.2), "test");
    filled = true;
  }
  return buffer;
}

}  // namespace

TEST(LookupTransform, ComposesTheChainAtTheStamp) {
  const auto t = hardware::lookupTransform(filledBuffer(), "base_link", "calibrated/cam", ros::Time(11), 0.0);
  EXPECT_EQ(t.header.frame_id, "base_link");
  EXPECT_EQ(t.child_frame_id, "calibrated/cam");
  EXPECT_NEAR(t.transform.translation.x, 0.6, 1e-9);  // 0.5 + halfway between 0 and 0.2
  EXPECT_EQ(t.header.stamp, ros::Time(11));
}

TEST(LookupTransform, FailureNamesBothFramesAndTheKnownOnes) {
  try {
    hardware::lookupTransform(filledBuffer(), "base_link", "calibrated/stereo_left_optical_frame", ros::Time(11), 0.05);
    FAIL() << "expected an error";
  } catch (const BlockError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'calibrated/stereo_left_optical_frame'"), std::string::npos) << what;
    EXPECT_NE(what.find("'base_link'"), std::string::npos) << what;
    EXPECT_NE(what.find("calibrated/cam"), std::string::npos) << what;  // the frames TF does know
  }
  try {  // a time outside the history: extrapolation
    hardware::lookupTransform(filledBuffer(), "base_link", "calibrated/cam", ros::Time(30), 0.05);
    FAIL() << "expected an error";
  } catch (const BlockError& e) {
    EXPECT_NE(std::string(e.what()).find("t = 30.000"), std::string::npos) << e.what();
  }
}

TEST(LookupTransform, EmptyFramePropertiesAreNamed) {
  BlockHarness h("imagenets/LookupTransform");
  EXPECT_EQ(h.block().inputs().size(), 1u);
  h.set("source_frame", std::string(""));
  EXPECT_NE(h.runError().find("property 'source_frame'"), std::string::npos);
  h.set("source_frame", std::string("cam")).set("target_frame", std::string(""));
  EXPECT_NE(h.runError().find("property 'target_frame'"), std::string::npos);
}
