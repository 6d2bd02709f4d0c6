#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(BuildFrame, BuildRejectsBadRotationAndMixedFrames) {
  BlockHarness build("imagenets/BuildFrame");
  geometry_msgs::Vector3Stamped::Ptr translation(new geometry_msgs::Vector3Stamped);
  translation->header.frame_id = "base";
  geometry_msgs::QuaternionStamped::Ptr rotation(new geometry_msgs::QuaternionStamped);
  rotation->header.frame_id = "base";
  rotation->quaternion.x = 1;
  rotation->quaternion.w = 1;  // norm sqrt 2
  build.input("translation", translation).input("rotation", rotation);
  EXPECT_NE(build.runError().find("input 'rotation': quaternion"), std::string::npos);
  rotation->quaternion.x = 0;
  rotation->header.frame_id = "camera";
  EXPECT_NE(build.runError().find("in frame 'base' but input 'rotation' in 'camera'"), std::string::npos);
  EXPECT_FALSE(build.hasOutput("frame"));
}
