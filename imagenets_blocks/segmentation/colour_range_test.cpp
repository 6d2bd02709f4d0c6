#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(ColourRange, SelectsRedAcrossTheHueWrap) {
  // Four pixels: red (hue 0), dark red-magenta (hue ~175), green, blue.
  cv::Mat in(1, 4, CV_8UC3);
  in.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  in.at<cv::Vec3b>(0, 1) = {30, 0, 200};
  in.at<cv::Vec3b>(0, 2) = {0, 255, 0};
  in.at<cv::Vec3b>(0, 3) = {255, 0, 0};
  BlockHarness h("imagenets/ColourRange");
  h.set("lower", std::vector<double>{170, 100, 100}).set("upper", std::vector<double>{10, 255, 255});
  h.input("image", toImageMsg(in, "bgr8", std_msgs::Header()));
  h.run();
  auto d = h.output<sensor_msgs::Image>("image")->data;
  EXPECT_EQ(d, (std::vector<uint8_t>{255, 255, 0, 0}));
  // The same pixels given as rgb8 are other colours: blue pixel 3 becomes red.
  h.input("image", toImageMsg(in, "rgb8", std_msgs::Header()));
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->data[3], 255);
  // BGR box: only green.
  h.set("space", "bgr").set("lower", std::vector<double>{0, 200, 0}).set("upper", std::vector<double>{50, 255, 50});
  h.input("image", toImageMsg(in, "bgr8", std_msgs::Header()));
  h.run();
  EXPECT_EQ(h.output<sensor_msgs::Image>("image")->data, (std::vector<uint8_t>{0, 0, 255, 0}));
}

TEST(ColourRange, BadBoundsAndGrayInputAreNamedErrors) {
  BlockHarness h("imagenets/ColourRange");
  h.input("image", toImageMsg(cv::Mat(2, 2, CV_8UC3), "bgr8", std_msgs::Header()));
  h.set("lower", std::vector<double>{1, 2});
  EXPECT_NE(h.runError().find("property 'lower': 2 values, expected 3"), std::string::npos);
  h.set("lower", std::vector<double>{0, 0, 0});
  h.input("image", toImageMsg(cv::Mat(2, 2, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("encoding 'mono8' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
}
