// The plot helpers: where the data, the chosen value and the missing samples land.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "imagenets/vision/plot.h"

using namespace imagenets;

namespace {

imagenets::FeedbackTrace sweep() {
  imagenets::FeedbackTrace t;
  t.block = "threshold";
  t.property = "threshold";
  t.score = "detect.confidence";
  t.maximize = true;
  for (int v = 40; v <= 80; v += 5) {
    t.values.push_back(v);
    t.scores.push_back(1.0 - (v - 60) * (v - 60) / 400.0);
  }
  t.scores[1] = std::nan("");  // 45: no score
  t.found = true;
  t.chosen_value = 60;
  t.chosen_score = 1.0;
  t.candidates = t.trials = 9;
  return t;
}

bool colourNear(const cv::Mat& img, cv::Point2d p, const cv::Scalar& colour, int radius) {
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const int x = cvRound(p.x) + dx, y = cvRound(p.y) + dy;
      if (x < 0 || y < 0 || x >= img.cols || y >= img.rows) continue;
      const cv::Vec3b c = img.at<cv::Vec3b>(y, x);
      if (std::abs(c[0] - colour[0]) + std::abs(c[1] - colour[1]) + std::abs(c[2] - colour[2]) < 40) return true;
    }
  }
  return false;
}

}  // namespace

TEST(Plot, FeedbackTraceMarksChosenValueAndMissingScores) {
  plot::Axes axes;
  const cv::Mat img = plot::plotFeedbackTrace(sweep(), 640, 400, &axes);
  ASSERT_EQ(img.type(), CV_8UC3);
  EXPECT_EQ(img.size(), cv::Size(640, 400));
  // The axes span the data: 40..80 on x, the scores on y.
  EXPECT_LE(axes.x_min, 40);
  EXPECT_GE(axes.x_max, 80);
  EXPECT_LE(axes.y_min, 0.0);
  EXPECT_GE(axes.y_max, 1.0);
  // The chosen value: a ring of radius 6 around (60, 1.0) in the marker colour.
  const cv::Point2d chosen = axes.toPixel(60, 1.0);
  EXPECT_TRUE(colourNear(img, chosen + cv::Point2d(6, 0), plot::kMarkerColor, 1));
  // Its dashed vertical line reaches the bottom half of the plot too.
  EXPECT_TRUE(colourNear(img, axes.toPixel(60, axes.y_min + 0.3 * (axes.y_max - axes.y_min)), plot::kMarkerColor, 5));
  // A sample with a score: a dot in the series colour.
  plot::Series defaults;
  EXPECT_TRUE(colourNear(img, axes.toPixel(50, 0.75), defaults.color, 1));
  // The NaN at 45: a cross near the bottom of the plot area, no dot anywhere above it.
  const cv::Point2d missing = axes.toPixel(45, axes.y_min);
  EXPECT_TRUE(colourNear(img, missing + cv::Point2d(0, -6), plot::kMissingColor, 2));
  EXPECT_FALSE(colourNear(img, axes.toPixel(45, 1.0 - 225 / 400.0), defaults.color, 2));
  // Far from any data (top left of the area, above the 40..45 segment): background.
  EXPECT_EQ(img.at<cv::Vec3b>(cvRound(axes.toPixel(41, 0.98).y), cvRound(axes.toPixel(41, 0.98).x)),
            cv::Vec3b(255, 255, 255));
}

TEST(Plot, NoValidCandidateHasNoMarker) {
  auto t = sweep();
  t.found = false;
  for (auto& s : t.scores) s = std::nan("");
  plot::Axes axes;
  const cv::Mat img = plot::plotFeedbackTrace(t, 480, 300, &axes);
  // Every candidate is a missing cross; there is no chosen-value line in the plot area.
  for (double v : t.values) EXPECT_TRUE(colourNear(img, axes.toPixel(v, axes.y_min) + cv::Point2d(0, -6), plot::kMissingColor, 2)) << v;
  EXPECT_FALSE(colourNear(img, axes.toPixel(60, 0.5 * (axes.y_min + axes.y_max)), plot::kMarkerColor, 3));
}

TEST(Plot, SeriesErrors) {
  plot::Series s;
  s.x = {1, 2, 3};
  s.y = {1, 2};
  EXPECT_THROW(plot::plotSeries({s}, plot::Options{}), std::invalid_argument);
  s.y = {1, 2, 3};
  plot::Options tiny;
  tiny.width = 100;
  EXPECT_THROW(plot::plotSeries({s}, tiny), std::invalid_argument);
  // A constant series still gets a usable y range.
  s.y = {5, 5, 5};
  plot::Axes axes;
  plot::plotSeries({s}, plot::Options{}, &axes);
  EXPECT_LT(axes.y_min, 5);
  EXPECT_GT(axes.y_max, 5);
}
