#include <gtest/gtest.h>
#include <geometry_msgs/PoseStamped.h>

#include "frame_test_util.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

namespace {

geometry_msgs::PoseStamped::Ptr pose(const Eigen::Isometry3d& t, const std::string& frame) {
  geometry_msgs::PoseStamped::Ptr p(new geometry_msgs::PoseStamped);
  p->header.frame_id = frame;
  p->header.stamp = ros::Time(12, 345);
  p->pose = imagenets::frames::toPose(t);
  return p;
}

}  // namespace

TEST(PoseToFrame, KeepsPoseAndHeaderAndNamesTheChild) {
  const Eigen::Isometry3d t = isometry(0.1, -0.2, 0.6, 2.5, Eigen::Vector3d(1, 2, 3));
  BlockHarness h("imagenets/PoseToFrame");
  h.set("child_frame_id", std::string("gripper_marker"));
  h.input("pose", pose(t, "stereo_left_optical_frame"));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "stereo_left_optical_frame");
  EXPECT_EQ(out->header.stamp, ros::Time(12, 345));
  EXPECT_EQ(out->child_frame_id, "gripper_marker");
  EXPECT_TRUE(toEigen(*out).isApprox(t, 1e-12));
}

TEST(PoseToFrame, FrameIdPropertyOverridesTheHeader) {
  BlockHarness h("imagenets/PoseToFrame");
  h.set("frame_id", std::string("camera"));
  h.input("pose", pose(isometry(1, 2, 3), "other"));
  h.run();
  auto out = h.output<geometry_msgs::TransformStamped>("frame");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.frame_id, "camera");
  EXPECT_EQ(out->child_frame_id, "object");  // the default child name
  EXPECT_NEAR(out->transform.translation.z, 3, 1e-12);
}

TEST(PoseToFrame, RejectsABadQuaternionAndAnEmptyChild) {
  BlockHarness h("imagenets/PoseToFrame");
  auto bad = pose(isometry(0, 0, 1), "camera");
  bad->pose.orientation.w = 0;  // all-zero quaternion
  const std::string error = h.input("pose", bad).runError();
  EXPECT_NE(error.find("input 'pose'"), std::string::npos) << error;
  EXPECT_FALSE(h.hasOutput("frame"));

  BlockHarness empty("imagenets/PoseToFrame");
  empty.set("child_frame_id", std::string(""));
  EXPECT_NE(empty.input("pose", pose(isometry(0, 0, 1), "camera")).runError().find("property 'child_frame_id'"),
            std::string::npos);
}
