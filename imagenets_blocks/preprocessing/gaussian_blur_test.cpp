#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {
cv::Mat pixels(const sensor_msgs::Image& msg) {
  return cv::Mat(msg.height, msg.width, CV_8UC1, const_cast<uint8_t*>(msg.data.data()), msg.step);
}
}  // namespace

TEST(GaussianBlur, SpreadsASpeckAndKeepsAnEdge) {
  // A one-pixel speck (what image noise leaves after a threshold) and a wide dark bar.
  cv::Mat in(20, 20, CV_8UC1, cv::Scalar(200));
  in.at<uchar>(5, 5) = 0;
  in.colRange(10, 20).setTo(20);
  BlockHarness h("imagenets/GaussianBlur");
  h.set("kernel_size", 3);
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  const auto out_msg = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out_msg);
  EXPECT_EQ(out_msg->encoding, "mono8");
  const cv::Mat out = pixels(*out_msg);
  // 3x3 Gaussian (1 2 1)^2 / 16: the speck keeps 4/16 of its depth, so a threshold of 100 no longer
  // sees it; its neighbours darken a little.
  EXPECT_NEAR(out.at<uchar>(5, 5), 200 - 200 * 4 / 16, 1);
  EXPECT_NEAR(out.at<uchar>(5, 6), 200 - 200 * 2 / 16, 1);
  // The bar's inside is unchanged; its edge is the mid-level between the two sides.
  EXPECT_EQ(out.at<uchar>(15, 15), 20);
  EXPECT_EQ(out.at<uchar>(15, 5), 200);
  EXPECT_NEAR(out.at<uchar>(15, 10), 20 + (200 - 20) / 4, 1);
}

TEST(GaussianBlur, AnEvenKernelIsAnErrorNamingIt) {
  BlockHarness h("imagenets/GaussianBlur");
  h.set("kernel_size", 4);
  h.input("image", toImageMsg(cv::Mat(8, 8, CV_8UC1, cv::Scalar(9)), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("property 'kernel_size': 4 is even"), std::string::npos) << h.runError();
}
