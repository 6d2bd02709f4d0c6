#include <gtest/gtest.h>
#include <imagenets/Polygons.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(FindContours, RectanglesLargestFirstSpecksDropped) {
  cv::Mat in(60, 80, CV_8UC1, cv::Scalar(0));
  in(cv::Rect(40, 30, 6, 6)).setTo(255);   // contour area 5*5 = 25
  in(cv::Rect(5, 5, 20, 10)).setTo(255);   // contour area 19*9 = 171
  in(cv::Rect(70, 50, 2, 2)).setTo(255);   // area 1: dropped
  BlockHarness h("imagenets/FindContours");
  h.input("image", toImageMsg(in, "mono8", std_msgs::Header()));
  h.run();
  auto out = h.output<imagenets::Polygons>("contours");
  ASSERT_TRUE(out);
  ASSERT_EQ(out->polygons.size(), 2u);
  const auto& big = out->polygons[0].points;
  ASSERT_EQ(big.size(), 4u);  // an axis-aligned rectangle needs only its corners
  std::vector<cv::Point2f> pts;
  for (const auto& p : big) pts.emplace_back(p.x, p.y);
  EXPECT_DOUBLE_EQ(cv::contourArea(pts), 171.0);
  EXPECT_EQ(cv::boundingRect(pts), cv::Rect(5, 5, 20, 10));
  h.set("max_count", 1);
  h.run();
  EXPECT_EQ(h.output<imagenets::Polygons>("contours")->polygons.size(), 1u);
  h.input("image", toImageMsg(cv::Mat(4, 4, CV_8UC3), "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': encoding 'bgr8' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("contours"));
}
