#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(HistogramEqualization, SpreadsANarrowHistogram) {
  // 32 gray levels 100..131, equally frequent: equalisation maps them evenly onto 0..255.
  cv::Mat in(32, 32, CV_8UC1);
  for (int r = 0; r < 32; ++r) in.row(r).setTo(100 + r);
  BlockHarness h("imagenets/HistogramEqualization");
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  const cv::Mat out = cv::Mat(32, 32, CV_8UC1, const_cast<uint8_t*>(h.output<sensor_msgs::Image>("image")->data.data()));
  EXPECT_EQ(out.at<uchar>(0, 0), 0);
  EXPECT_EQ(out.at<uchar>(31, 0), 255);
  // Level k of 32 lands at round(255 * k / 31).
  EXPECT_NEAR(out.at<uchar>(16, 0), 255.0 * 16 / 31, 1.0);
  // CLAHE runs too and keeps the order of the levels.
  h.set("clip_limit", 2.0).set("tiles", 2);
  h.run();
  const auto& data = h.output<sensor_msgs::Image>("image")->data;
  EXPECT_LT(data[0], data[31 * 32]);
}

TEST(HistogramEqualization, ColourKeepsHueAndBadInputFails) {
  cv::Mat in(16, 16, CV_8UC3);
  for (int r = 0; r < 16; ++r) in.row(r).setTo(cv::Scalar(100 + r, 100 + r, 100 + r));
  BlockHarness h("imagenets/HistogramEqualization");
  h.input("image", toImageMsg(in, "bgr8", std_msgs::Header()));
  h.run();
  const auto& d = h.output<sensor_msgs::Image>("image")->data;
  const size_t last = (15 * 16) * 3;
  EXPECT_NEAR(d[last], d[last + 1], 1);  // gray stays gray
  EXPECT_NEAR(d[last + 1], d[last + 2], 1);
  EXPECT_GT(d[last], 240);
  h.input("image", toImageMsg(cv::Mat(), "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': empty image"), std::string::npos);
}
