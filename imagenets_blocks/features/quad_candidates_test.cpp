#include <iostream>

#include <gtest/gtest.h>
#include <imagenets/Polygons.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {

// A dark image with a bright convex quadrilateral whose corners are known to sub-pixel accuracy:
// drawn at 16x resolution and area-averaged down (pixel centres at integer coordinates).
cv::Mat renderQuad(const std::vector<cv::Point2d>& corners, cv::Size size) {
  const int s = 16;
  cv::Mat big(size.height * s, size.width * s, CV_8UC1, cv::Scalar(30));
  std::vector<cv::Point> hi;
  for (const auto& c : corners) hi.emplace_back(cvRound((s * (c.x + 0.5) - 0.5) * 16), cvRound((s * (c.y + 0.5) - 0.5) * 16));
  cv::fillConvexPoly(big, hi, cv::Scalar(220), cv::LINE_8, 4);
  cv::Mat small;
  cv::resize(big, small, size, 0, 0, cv::INTER_AREA);
  return small;
}

imagenets::Polygons::Ptr contoursOf(const cv::Mat& gray) {
  cv::Mat binary;
  cv::threshold(gray, binary, 125, 255, cv::THRESH_BINARY);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(binary, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  imagenets::Polygons::Ptr out(new imagenets::Polygons);
  for (const auto& c : contours) {
    geometry_msgs::Polygon poly;
    for (const auto& p : c) {
      geometry_msgs::Point32 q;
      q.x = p.x;
      q.y = p.y;
      poly.points.push_back(q);
    }
    out->polygons.push_back(poly);
  }
  return out;
}

}  // namespace

TEST(QuadCandidates, SubPixelCornersOfARotatedSquare) {
  // Corners given counter-clockwise on screen; expected back clockwise from the top-left one.
  const std::vector<cv::Point2d> truth{{40.3, 22.7}, {28.6, 71.1}, {77.2, 83.4}, {89.1, 34.9}};
  const cv::Mat gray = renderQuad(truth, {120, 110});
  cv::Mat with_triangle = gray.clone();
  cv::fillConvexPoly(with_triangle, std::vector<cv::Point>{{5, 100}, {25, 100}, {15, 85}}, cv::Scalar(220));

  BlockHarness h("imagenets/QuadCandidates");
  h.input("contours", contoursOf(with_triangle)).input("image", toImageMsg(with_triangle, "mono8", std_msgs::Header()));
  h.run();
  auto out = h.output<imagenets::Polygons>("quads");
  ASSERT_TRUE(out);
  ASSERT_EQ(out->polygons.size(), 1u);  // the triangle is not a candidate
  const auto& q = out->polygons[0].points;
  ASSERT_EQ(q.size(), 4u);
  const std::vector<cv::Point2d> expected{truth[0], truth[3], truth[2], truth[1]};
  double refined_worst = 0;
  for (int i = 0; i < 4; ++i) {
    refined_worst = std::max(refined_worst, cv::norm(cv::Point2d(q[i].x, q[i].y) - expected[i]));
    EXPECT_LT(cv::norm(cv::Point2d(q[i].x, q[i].y) - expected[i]), 0.35)
        << "corner " << i << ": " << q[i].x << "," << q[i].y << " vs " << expected[i];
  }
  // (cornerSubPix on an L corner of an area-sampled edge keeps a small bias towards the inside, ~0.2 px.)
  // Without refinement the corners are only pixel-accurate (the refinement is doing the work).
  h.set("refine_window", 0);
  h.run();
  double worst = 0;
  const auto& raw = h.output<imagenets::Polygons>("quads")->polygons[0].points;
  for (int i = 0; i < 4; ++i) worst = std::max(worst, cv::norm(cv::Point2d(raw[i].x, raw[i].y) - expected[i]));
  EXPECT_GT(worst, 0.5);
  std::cout << "corner error refined " << refined_worst << " px, unrefined " << worst << " px\n";
}

TEST(QuadCandidates, SmallQuadsDroppedAndBadImageIsNamedError) {
  const cv::Mat gray = renderQuad({{20, 20}, {26, 20}, {26, 26}, {20, 26}}, {60, 60});
  BlockHarness h("imagenets/QuadCandidates");
  h.input("contours", contoursOf(gray)).input("image", toImageMsg(gray, "mono8", std_msgs::Header()));
  h.run();
  EXPECT_TRUE(h.output<imagenets::Polygons>("quads")->polygons.empty());  // sides 6 < min_side 10
  h.input("image", toImageMsg(cv::Mat(60, 60, CV_8UC3), "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'image': encoding 'bgr8' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("quads"));
}
