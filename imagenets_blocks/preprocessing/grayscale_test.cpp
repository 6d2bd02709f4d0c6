#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(Grayscale, ConvertsColourAndKeepsTheHeader) {
  std_msgs::Header header;
  header.frame_id = "camera";
  header.stamp = ros::Time(12.5);
  BlockHarness h("imagenets/Grayscale");
  h.input("image", toImageMsg(cv::Mat(2, 2, CV_8UC3, cv::Scalar(0, 0, 255)), "bgr8", header));  // red
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  EXPECT_EQ(out->encoding, "mono8");
  EXPECT_EQ(out->header.frame_id, "camera");
  EXPECT_EQ(out->header.stamp, ros::Time(12.5));
  EXPECT_EQ(out->data[0], 76);  // 0.299 * 255
  h.input("image", toImageMsg(cv::Mat(2, 2, CV_8UC3, cv::Scalar(0, 0, 255)), "rgb8", header));  // blue
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->data[0], 29);  // 0.114 * 255
}

TEST(Grayscale, PassesAGrayImageOnAsTheSameMessage) {
  BlockHarness h("imagenets/Grayscale");
  const sensor_msgs::ImagePtr gray = toImageMsg(cv::Mat(2, 2, CV_8UC1, cv::Scalar(9)), "mono8", std_msgs::Header());
  h.input("image", gray);
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image").get(), gray.get());
}

TEST(Grayscale, AnEncodingItCannotConvertIsANamedError) {
  BlockHarness h("imagenets/Grayscale");
  h.input("image", toImageMsg(cv::Mat(2, 2, CV_16UC1), "mono16", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': encoding 'mono16' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
}
