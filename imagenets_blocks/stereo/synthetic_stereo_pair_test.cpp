#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "stereo_test_util.h"

using namespace imagenets::blocks;

namespace {
cv::Mat view(const sensor_msgs::Image& m, int type) {
  return cv::Mat(m.height, m.width, type, const_cast<uint8_t*>(m.data.data()), m.step);
}
double meanAbsDiff(const cv::Mat& a, const cv::Mat& b) { return cv::mean(cv::abs(a - b) + cv::abs(b - a))[0]; }
}  // namespace

TEST(SyntheticStereoPair, RightImageIsLeftShiftedByTheDisparity) {
  auto pair = test::syntheticPair();
  auto left_info = pair.output<sensor_msgs::CameraInfo>("left_info");
  auto right_info = pair.output<sensor_msgs::CameraInfo>("right_info");
  EXPECT_DOUBLE_EQ(right_info->P[3], -300 * 0.1);
  EXPECT_DOUBLE_EQ(left_info->P[3], 0);
  const cv::Mat depth = view(*pair.output<sensor_msgs::Image>("depth"), CV_32FC1);
  EXPECT_FLOAT_EQ(depth.at<float>(120, 160), 1.25f);  // board in the centre
  EXPECT_FLOAT_EQ(depth.at<float>(10, 10), 2.5f);     // wall in the corner
  cv::Mat left, right;
  cv::cvtColor(view(*pair.output<sensor_msgs::Image>("left"), CV_8UC3), left, cv::COLOR_BGR2GRAY);
  cv::cvtColor(view(*pair.output<sensor_msgs::Image>("right"), CV_8UC3), right, cv::COLOR_BGR2GRAY);
  // Wall strip (top rows): left(u) = right(u - 12).
  const cv::Rect wall_l(40, 5, 240, 20), wall_r = wall_l - cv::Point(12, 0);
  EXPECT_LT(meanAbsDiff(left(wall_l), right(wall_r)), 1.0);
  EXPECT_GT(meanAbsDiff(left(wall_l), right(wall_l)), 10.0);  // the texture is not flat
  // Board centre: left(u) = right(u - 24).
  const cv::Rect board_l(140, 100, 40, 40), board_r = board_l - cv::Point(24, 0);
  EXPECT_LT(meanAbsDiff(left(board_l), right(board_r)), 1.0);
}
