#include <gtest/gtest.h>
#include <imagenets/MarkerDetection.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {
imagenets::MarkerDetection::Ptr detection() {
  imagenets::MarkerDetection::Ptr d(new imagenets::MarkerDetection);
  d->marker = "gripper";
  d->found = true;
  d->confidence = 0.9;
  for (auto [x, y] : {std::pair{40.0, 40.0}, {120.0, 40.0}, {120.0, 120.0}, {40.0, 120.0}}) {
    geometry_msgs::Point p;
    p.x = x;
    p.y = y;
    d->points.push_back(p);
  }
  // Marker 1 m ahead of the camera on the optical axis, facing it.
  d->pose.position.z = 1.0;
  d->pose.orientation.w = 1;
  return d;
}
cv::Vec3b at(const sensor_msgs::Image& m, int r, int c) { return cv::Vec3b(&m.data[r * m.step + 3 * c]); }
}  // namespace

TEST(DrawDetection, CornersAndProjectedPoseAxes) {
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->K = {500, 0, 100, 0, 500, 150, 0, 0, 1};
  info->D = {0, 0, 0, 0, 0};
  BlockHarness h("imagenets/DrawDetection");
  h.set("axis_length", 0.05).set("thickness", 1);
  h.input("image", toImageMsg(cv::Mat(200, 200, CV_8UC1, cv::Scalar(0)), "mono8", std_msgs::Header()));
  h.input("detection", detection()).input("camera_info", info);
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  EXPECT_GT(at(*out, 40, 80)[1], 150);  // top edge of the outer quad: green
  EXPECT_EQ(at(*out, 80, 80), cv::Vec3b(0, 0, 0));  // inside: untouched
  // The x axis runs from the principal point (100, 150) to (100 + 500 * 0.05, 150) = (125, 150): red.
  EXPECT_GT(at(*out, 150, 115)[2], 150);
  EXPECT_LT(at(*out, 150, 115)[1], 100);
  // The y axis (camera y is down) ends at (100, 175): green.
  EXPECT_GT(at(*out, 165, 100)[1], 150);
}

TEST(DrawDetection, NotFoundAndBadPoseAreHandled) {
  auto d = detection();
  d->found = false;
  BlockHarness h("imagenets/DrawDetection");
  h.input("image", toImageMsg(cv::Mat(200, 200, CV_8UC3, cv::Scalar(0, 0, 0)), "bgr8", std_msgs::Header()));
  h.input("detection", d);
  h.run();  // draws "not found", no corners
  EXPECT_EQ(at(*h.output<sensor_msgs::Image>("image"), 40, 80), cv::Vec3b(0, 0, 0));
  d = detection();
  d->pose.orientation.w = 3;
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->K = {500, 0, 100, 0, 500, 150, 0, 0, 1};
  h.input("detection", d).input("camera_info", info);
  EXPECT_NE(h.runError().find("input 'detection' pose: quaternion"), std::string::npos) << h.runError();
  h.clear("detection");
  EXPECT_EQ(h.runError(), "input 'detection' has no value");
  EXPECT_FALSE(h.hasOutput("image"));
}
