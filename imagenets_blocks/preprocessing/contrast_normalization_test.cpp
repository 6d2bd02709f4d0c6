#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(ContrastNormalization, StretchesToTheFullRange) {
  cv::Mat in(2, 3, CV_8UC1);
  in.at<uchar>(0, 0) = 50;
  in.at<uchar>(0, 1) = 110;
  in.at<uchar>(0, 2) = 150;
  in.row(1).setTo(75);
  BlockHarness h("imagenets/ContrastNormalization");
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->data[0], 0);
  EXPECT_EQ(out->data[1], 153);  // (110 - 50) * 2.55
  EXPECT_EQ(out->data[2], 255);
  EXPECT_EQ(out->data[3], 64);   // 25 * 2.55 = 63.75
  h.set("low", 10).set("high", 20);
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->data[1], 16);  // 10 + 60 * 0.1
}

TEST(ContrastNormalization, BadInputIsNamedError) {
  BlockHarness h("imagenets/ContrastNormalization");
  h.input("image", toImageMsg(cv::Mat(4, 4, CV_16UC1), "16UC1", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': encoding '16UC1' not accepted"), std::string::npos);
  h.input("image", toImageMsg(cv::Mat(4, 4, CV_8UC1, cv::Scalar(3)), "mono8", std_msgs::Header()));
  h.set("low", 200).set("high", 100);
  EXPECT_NE(h.runError().find("low must be below high"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
}
