#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <gtest/gtest.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

TEST(MedianTranslation, PerAxisMedianIgnoresOutliers) {
  geometry_msgs::PoseArray::Ptr set(new geometry_msgs::PoseArray);
  // Five measurements around (1, 2, 3) with one wild value in a different axis each time.
  for (auto t : {isometry(1.0, 2.0, 3.0), isometry(9.0, 2.1, 3.0), isometry(1.1, -7.0, 2.9), isometry(0.9, 1.9, 50.0),
                 isometry(1.05, 2.05, 3.1)}) {
    set->poses.push_back(imagenets::frames::toPose(t));
  }
  BlockHarness h("imagenets/MedianTranslation");
  h.input("poses", set);
  h.run();
  auto out = h.output<geometry_msgs::Vector3Stamped>("translation");
  ASSERT_TRUE(out);
  EXPECT_DOUBLE_EQ(out->vector.x, 1.05);  // sorted x: 0.9 1.0 1.05 1.1 9
  EXPECT_DOUBLE_EQ(out->vector.y, 2.0);   // sorted y: -7 1.9 2.0 2.05 2.1
  EXPECT_DOUBLE_EQ(out->vector.z, 3.0);   // sorted z: 2.9 3.0 3.0 3.1 50
}

TEST(MedianTranslation, NaNPositionIsNamedError) {
  geometry_msgs::PoseArray::Ptr set(new geometry_msgs::PoseArray);
  set->poses.push_back(imagenets::frames::toPose(isometry(1, 2, 3)));
  set->poses[0].position.x = std::nan("");
  BlockHarness h("imagenets/MedianTranslation");
  h.input("poses", set);
  EXPECT_NE(h.runError().find("input 'poses' pose 0: position.x is nan"), std::string::npos) << h.runError();
  EXPECT_FALSE(h.hasOutput("translation"));
}
