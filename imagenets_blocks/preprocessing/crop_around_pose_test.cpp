#include <gtest/gtest.h>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {

sensor_msgs::CameraInfo::Ptr camera(int width, int height) {
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = width;
  info->height = height;
  info->K = {100, 0, 100, 0, 100, 50, 0, 0, 1};
  return info;
}

geometry_msgs::PoseStamped::Ptr poseAt(double x, double y, double z) {
  geometry_msgs::PoseStamped::Ptr p(new geometry_msgs::PoseStamped);
  p->pose.position.x = x;
  p->pose.position.y = y;
  p->pose.position.z = z;
  p->pose.orientation.w = 1;
  return p;
}

cv::Mat ramp(int width, int height) {
  cv::Mat in(height, width, CV_8UC1);
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) in.at<uchar>(r, c) = static_cast<uchar>((c + r) % 256);
  return in;
}

}  // namespace

TEST(CropAroundPose, CropsAroundTheProjectedPoseAndRecordsTheRegionAsRoi) {
  BlockHarness h("imagenets/CropAroundPose");
  h.set("size", 0.2).set("margin_px", 10);
  // (0.1, 0, 1) projects to (110, 50); 0.2 m at 1 m is 20 px: half side 10 + 20 = 30.
  h.input("image", toImageMsg(ramp(200, 100), "mono8", std_msgs::Header()))
      .input("camera_info", camera(200, 100))
      .input("pose", poseAt(0.1, 0, 1));
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->width, 60u);
  EXPECT_EQ(out->height, 60u);
  EXPECT_EQ(out->data[0], (80 + 20) % 256);  // pixel (80, 20) of the input
  auto info = h.output<sensor_msgs::CameraInfo>("camera_info");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->roi.x_offset, 80u);
  EXPECT_EQ(info->roi.y_offset, 20u);
  EXPECT_EQ(info->roi.width, 60u);
  EXPECT_EQ(info->roi.height, 60u);
  EXPECT_DOUBLE_EQ(info->K[2], 100);  // K stays the full image's (ROS roi convention)
  EXPECT_EQ(info->width, 200u);
}

TEST(CropAroundPose, ClipsToTheImageAndFallsBackToTheWholeImage) {
  BlockHarness h("imagenets/CropAroundPose");
  h.set("size", 0.2).set("margin_px", 10);
  h.input("image", toImageMsg(ramp(200, 100), "mono8", std_msgs::Header())).input("camera_info", camera(200, 100));
  h.input("pose", poseAt(-0.9, -0.4, 1));  // projects to (10, 10): clipped at the corner
  h.run();
  auto info = h.output<sensor_msgs::CameraInfo>("camera_info");
  EXPECT_EQ(info->roi.x_offset, 0u);
  EXPECT_EQ(info->roi.width, 40u);
  EXPECT_EQ(info->roi.height, 40u);
  for (auto pose : {poseAt(0, 0, -1), poseAt(0, 0, 0.01), poseAt(50, 0, 1)}) {  // behind, too close, outside
    h.input("pose", pose);
    h.run();
    EXPECT_EQ(h.output<sensor_msgs::CameraInfo>("camera_info")->roi.width, 200u);
    EXPECT_EQ(h.output<sensor_msgs::Image>("image")->width, 200u);
  }
  h.clear("pose");
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->height, 100u);
}

TEST(CropAroundPose, MismatchedCameraInfoIsANamedError) {
  BlockHarness h("imagenets/CropAroundPose");
  h.input("image", toImageMsg(ramp(200, 100), "mono8", std_msgs::Header())).input("camera_info", camera(100, 100));
  EXPECT_NE(h.runError().find("input 'image' is 200x100, input 'camera_info' is for 100x100 images"), std::string::npos);
  auto region = camera(200, 100);
  region->roi.width = 50;
  region->roi.height = 50;
  h.input("camera_info", region);
  EXPECT_NE(h.runError().find("input 'camera_info' already describes a region"), std::string::npos);
}
