#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(CropRoi, CropsImageAndShiftsCameraModel) {
  cv::Mat in(8, 10, CV_8UC1);
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 10; ++c) in.at<uchar>(r, c) = static_cast<uchar>(c + 10 * r);
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = 10;
  info->height = 8;
  info->K = {100, 0, 5, 0, 100, 4, 0, 0, 1};
  info->P = {100, 0, 5, 0, 0, 100, 4, 0, 0, 0, 1, 0};
  BlockHarness h("imagenets/CropRoi");
  h.set("x", 2).set("y", 3).set("width", 4).set("height", 2);
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header())).input("camera_info", info);
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->width, 4u);
  EXPECT_EQ(out->height, 2u);
  EXPECT_EQ(out->data[0], 32);
  EXPECT_EQ(out->data[out->step + 3], 45);
  auto model = h.output<sensor_msgs::CameraInfo>("camera_info");
  ASSERT_TRUE(model);
  EXPECT_DOUBLE_EQ(model->K[2], 3);
  EXPECT_DOUBLE_EQ(model->K[5], 1);
  EXPECT_DOUBLE_EQ(model->P[6], 1);
  EXPECT_EQ(model->width, 4u);
}

TEST(CropRoi, RegionOutsideImageIsNamedError) {
  BlockHarness h("imagenets/CropRoi");
  h.set("x", 8).set("width", 4);
  h.input("image", toImageMsg(cv::Mat(8, 10, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("region x 8, y 0, 4x8 is not inside the 10x8 input 'image'"), std::string::npos)
      << h.runError();
  EXPECT_FALSE(h.hasOutput("image"));
}
