#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/PointCloud2.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"
#include "imagenets/vision/point_cloud.h"

using namespace imagenets::blocks;

namespace {
sensor_msgs::CameraInfo::Ptr info(double tx) {
  sensor_msgs::CameraInfo::Ptr i(new sensor_msgs::CameraInfo);
  i->width = 4;
  i->height = 3;
  i->P = {200, 0, 1.5, tx, 0, 200, 1, 0, 0, 0, 1, 0};
  return i;
}
}  // namespace

TEST(DisparityToPointCloud, HandComputedPoints) {
  // fx 200, baseline 0.1 (P_r[3] = -20): d = 8 -> Z = 200 * 0.1 / 8 = 2.5 m.
  cv::Mat d(3, 4, CV_32FC1, cv::Scalar(8.0f));
  d.at<float>(0, 0) = NAN;   // unknown
  d.at<float>(0, 1) = 0.5f;  // Z = 40 m > max_depth
  cv::Mat colour(3, 4, CV_8UC3, cv::Scalar(10, 20, 30));  // B, G, R
  BlockHarness h("imagenets/DisparityToPointCloud");
  h.input("disparity", toImageMsg(d, "32FC1", std_msgs::Header()))
      .input("left_info", info(0))
      .input("right_info", info(-20))
      .input("image", toImageMsg(colour, "bgr8", std_msgs::Header()));
  h.run();
  bool has_colour = false;
  auto points = imagenets::cloud::readPoints(*h.output<sensor_msgs::PointCloud2>("cloud"), &has_colour);
  ASSERT_EQ(points.size(), 10u);
  EXPECT_TRUE(has_colour);
  // First kept point: pixel (u 2, v 0): X = (2 - 1.5) * 2.5 / 200, Y = (0 - 1) * 2.5 / 200.
  EXPECT_FLOAT_EQ(points[0].z, 2.5f);
  EXPECT_FLOAT_EQ(points[0].x, 0.5f * 2.5f / 200);
  EXPECT_FLOAT_EQ(points[0].y, -2.5f / 200);
  EXPECT_EQ(points[0].r, 30);
  EXPECT_EQ(points[0].b, 10);
}

TEST(DisparityToPointCloud, MissingOrBadModelsAreNamedErrors) {
  BlockHarness h("imagenets/DisparityToPointCloud");
  h.input("disparity", toImageMsg(cv::Mat(3, 4, CV_32FC1, cv::Scalar(1)), "32FC1", std_msgs::Header()));
  h.input("left_info", info(0));
  EXPECT_EQ(h.runError(), "input 'right_info' has no value");
  h.input("right_info", info(0));
  EXPECT_NE(h.runError().find("gives no positive baseline"), std::string::npos);
  h.input("right_info", info(-20));
  h.input("disparity", toImageMsg(cv::Mat(3, 4, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'disparity': encoding 'mono8' not accepted"), std::string::npos);
  h.input("disparity", toImageMsg(cv::Mat(5, 4, CV_32FC1), "32FC1", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'left_info' is for 4x3 images"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("cloud"));
}
