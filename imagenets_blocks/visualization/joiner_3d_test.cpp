#include <gtest/gtest.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "../frames/frame_test_util.h"
#include "imagenets/vision/point_cloud.h"

using namespace imagenets::blocks;
using namespace imagenets::blocks::test;

namespace {
const visualization_msgs::Marker* find(const visualization_msgs::MarkerArray& a, const std::string& ns, int nth = 0) {
  for (const auto& m : a.markers) {
    if (m.ns == ns && nth-- == 0) return &m;
  }
  return nullptr;
}
}  // namespace

TEST(Joiner3D, ChainsFramesAndPlacesObjectsAndClouds) {
  BlockHarness h("imagenets/Joiner3D");
  h.set("fixed_frame", "robot").set("axis_length", 0.2);
  // robot -> camera: 1 m up, turned 90 deg about z; camera -> marker: 0.5 m along camera x.
  h.input("frame_1", frame(isometry(0, 0, 1, M_PI / 2), "robot", "camera"));
  h.input("frame_2", frame(isometry(0.5, 0, 0), "camera", "marker"));
  visualization_msgs::Marker::Ptr box(new visualization_msgs::Marker);
  box->header.frame_id = "marker";
  box->ns = "board";
  box->type = visualization_msgs::Marker::CUBE;
  box->pose.orientation.w = 1;
  box->pose.position.z = 0.1;
  h.input("object_1", box);
  auto cloud = imagenets::cloud::makeCloud({{0, 0, 2, 255, 0, 0}, {0.1f, 0, 2, 0, 255, 0}}, true);
  cloud->header.frame_id = "camera";
  h.input("cloud_1", cloud);
  h.run();
  auto scene = h.output<visualization_msgs::MarkerArray>("markers");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->markers[0].action, visualization_msgs::Marker::DELETEALL);
  // The marker's x axis (second triad, first arrow) starts at robot (0, 0.5, 1): camera x is robot y.
  const auto* marker_x = find(*scene, "frames", 3);
  ASSERT_TRUE(marker_x);
  EXPECT_EQ(marker_x->header.frame_id, "robot");
  EXPECT_NEAR(marker_x->points[0].x, 0, 1e-12);
  EXPECT_NEAR(marker_x->points[0].y, 0.5, 1e-12);
  EXPECT_NEAR(marker_x->points[0].z, 1, 1e-12);
  EXPECT_NEAR(marker_x->points[1].y, 0.7, 1e-12);  // 0.2 m axis along robot y
  EXPECT_EQ(find(*scene, "frame_names", 1)->text, "marker");
  // The box: 0.1 m along the marker's z (= robot z), in the robot frame.
  const auto* board = find(*scene, "board");
  ASSERT_TRUE(board);
  EXPECT_EQ(board->header.frame_id, "robot");
  EXPECT_NEAR(board->pose.position.z, 1.1, 1e-12);
  EXPECT_NEAR(board->pose.position.y, 0.5, 1e-12);
  // The cloud: drawn with the camera's pose, colours kept.
  const auto* points = find(*scene, "clouds");
  ASSERT_TRUE(points);
  EXPECT_EQ(points->points.size(), 2u);
  EXPECT_NEAR(points->pose.position.z, 1, 1e-12);
  EXPECT_FLOAT_EQ(points->colors[1].g, 1.0f);
  // TF: both input frames.
  auto tf = h.output<tf2_msgs::TFMessage>("tf");
  ASSERT_EQ(tf->transforms.size(), 2u);
  EXPECT_EQ(tf->transforms[1].child_frame_id, "marker");
}

TEST(Joiner3D, UnreachableFrameStaysInItsRootAndBadInputsFail) {
  BlockHarness h("imagenets/Joiner3D");
  h.set("fixed_frame", "robot");
  h.input("frame_1", frame(isometry(1, 2, 3), "world", "table"));
  h.run();
  EXPECT_EQ(find(*h.output<visualization_msgs::MarkerArray>("markers"), "frames")->header.frame_id, "world");
  h.input("frame_2", frame(isometry(0, 0, 0), "map", "table"));
  EXPECT_NE(h.runError().find("frame 'table' is given twice"), std::string::npos);
  auto nan = frame(isometry(0, 0, 0), "robot", "camera");
  nan->transform.rotation.x = std::nan("");
  h.input("frame_2", nan);
  EXPECT_NE(h.runError().find("input 'frame_2': orientation.x is nan"), std::string::npos) << h.runError();
  h.input("frame_1", frame(isometry(0, 0, 0), "b", "a")).input("frame_2", frame(isometry(0, 0, 0), "a", "b"));
  EXPECT_NE(h.runError().find("frames form a cycle"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("markers"));
}
