#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(OtsuThreshold, SplitsTwoLevelImageBetweenTheLevels) {
  // Half the pixels at 40, half at 200: Otsu's threshold lies between (OpenCV returns the
  // lower class's top level, 40); everything >40 is white.
  cv::Mat in(10, 10, CV_8UC1, cv::Scalar(40));
  in.colRange(5, 10).setTo(200);
  BlockHarness h("imagenets/OtsuThreshold");
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  const double t = h.output<std_msgs::Float64>("threshold")->data;
  EXPECT_GE(t, 40);
  EXPECT_LT(t, 200);
  const auto& d = h.output<sensor_msgs::Image>("image")->data;
  EXPECT_EQ(d[0], 0);
  EXPECT_EQ(d[9], 255);
  h.input("image", toImageMsg(in, "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError(), "");
  h.input("image", toImageMsg(cv::Mat(10, 10, CV_8UC3), "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("encoding 'bgr8' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("threshold"));
}
