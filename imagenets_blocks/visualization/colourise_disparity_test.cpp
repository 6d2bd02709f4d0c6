#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(ColouriseDisparity, MapsRangeToColourMapAndNaNToBlack) {
  cv::Mat d(1, 3, CV_32FC1);
  d.at<float>(0, 0) = 10;
  d.at<float>(0, 1) = 30;
  d.at<float>(0, 2) = NAN;
  BlockHarness h("imagenets/ColouriseDisparity");
  h.set("colour_map", "jet").input("disparity", toImageMsg(d, "32FC1", std_msgs::Header()));
  h.run();
  const auto& px = h.output<sensor_msgs::Image>("image")->data;
  cv::Mat ends(1, 2, CV_8UC1);
  ends.at<uchar>(0, 0) = 0;
  ends.at<uchar>(0, 1) = 255;
  cv::Mat expected;
  cv::applyColorMap(ends, expected, cv::COLORMAP_JET);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(px[c], expected.at<cv::Vec3b>(0, 0)[c]);      // 10 = auto min: cold end
    EXPECT_EQ(px[3 + c], expected.at<cv::Vec3b>(0, 1)[c]);  // 30 = auto max: warm end
    EXPECT_EQ(px[6 + c], 0);                                // NaN: black
  }
  cv::Mat none(2, 2, CV_32FC1, cv::Scalar(NAN));
  h.input("disparity", toImageMsg(none, "32FC1", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'disparity': no finite value"), std::string::npos);
  h.input("disparity", toImageMsg(cv::Mat(2, 2, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("encoding 'mono8' not accepted"), std::string::npos);
}
