#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "imagenets/vision/quadrilateral.h"

using imagenets::marker::convexQuadrilateral;

namespace {

// The outer boundary of a filled polygon drawn in a 200x200 image, as findContours traces it.
std::vector<cv::Point> outline(const std::vector<cv::Point>& polygon) {
  cv::Mat image = cv::Mat::zeros(200, 200, CV_8UC1);
  cv::fillPoly(image, std::vector<std::vector<cv::Point>>{polygon}, 255);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(image, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  return contours.at(0);
}

const cv::Rect2f kInside(3, 3, 194, 194);

}  // namespace

TEST(ConvexQuadrilateral, ASquareGivesItsCornersClockwise) {
  const auto quad = convexQuadrilateral(outline({{50, 50}, {50, 150}, {150, 150}, {150, 50}}), 0.05, 10, kInside);
  ASSERT_TRUE(quad);
  double signed_area = 0;  // positive with y down: clockwise on screen
  for (int i = 0; i < 4; ++i) signed_area += (*quad)[i].x * (*quad)[(i + 1) % 4].y - (*quad)[(i + 1) % 4].x * (*quad)[i].y;
  EXPECT_GT(signed_area, 0);
  for (const cv::Point2f& c : *quad) {
    EXPECT_TRUE((c.x == 50 || c.x == 150) && (c.y == 50 || c.y == 150)) << c;
  }
}

TEST(ConvexQuadrilateral, OtherShapesSmallOnesAndOnesAtTheBorderAreNone) {
  EXPECT_FALSE(convexQuadrilateral(outline({{100, 20}, {180, 170}, {20, 170}}), 0.05, 10, kInside));  // triangle
  EXPECT_FALSE(convexQuadrilateral(outline({{50, 50}, {50, 150}, {100, 60}, {150, 150}, {150, 50}}), 0.02, 10,
                                   kInside));  // not convex
  EXPECT_FALSE(convexQuadrilateral(outline({{50, 50}, {50, 58}, {58, 58}, {58, 50}}), 0.05, 10, kInside));  // sides 8 px
  EXPECT_FALSE(convexQuadrilateral(outline({{1, 50}, {1, 150}, {100, 150}, {100, 50}}), 0.05, 10, kInside));  // border
  EXPECT_FALSE(convexQuadrilateral(std::vector<cv::Point>{{60, 60}, {60, 61}, {61, 61}}, 0.05, 1, kInside));  // 3 points
}
