#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(PairCameraInfo, GivesTheModelTheImageHeader) {
  std_msgs::Header header;
  header.stamp = ros::Time(12, 34);
  header.frame_id = "left_optical";
  auto image = toImageMsg(cv::Mat(48, 64, CV_8UC1, cv::Scalar(7)), "mono8", header);
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = 64;
  info->height = 48;
  info->K[0] = 100;
  BlockHarness h("imagenets/PairCameraInfo");
  h.input("image", image).input("camera_info", info);
  h.run();
  auto out = h.output<sensor_msgs::CameraInfo>("camera_info");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->header.stamp, ros::Time(12, 34));
  EXPECT_EQ(out->header.frame_id, "left_optical");
  EXPECT_DOUBLE_EQ(out->K[0], 100);
  EXPECT_EQ(h.output<sensor_msgs::Image>("image").get(), image.get());  // passed through, not copied
}

TEST(PairCameraInfo, SizeMismatchAndMissingModelAreNamedErrors) {
  auto image = toImageMsg(cv::Mat(48, 64, CV_8UC1), "mono8", std_msgs::Header());
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = 640;
  info->height = 480;
  BlockHarness h("imagenets/PairCameraInfo");
  h.input("image", image).input("camera_info", info);
  EXPECT_NE(h.runError().find("input 'camera_info' is for 640x480 images, input 'image' is 64x48"), std::string::npos);
  h.clear("camera_info");
  EXPECT_EQ(h.runError(), "input 'camera_info' has no value");  // checked by the one invocation path
  h.input("camera_info", info).input("image", toImageMsg(cv::Mat(), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': empty image"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("camera_info"));
}
