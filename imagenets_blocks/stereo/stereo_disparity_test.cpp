#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <sensor_msgs/PointCloud2.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/point_cloud.h"
#include "stereo_test_util.h"

using namespace imagenets::blocks;

namespace {

// Median and valid fraction of the disparities in a region.
std::pair<double, double> medianIn(const sensor_msgs::Image& m, const cv::Rect& r) {
  const cv::Mat d(m.height, m.width, CV_32FC1, const_cast<uint8_t*>(m.data.data()), m.step);
  std::vector<float> valid;
  for (int v = r.y; v < r.br().y; ++v)
    for (int u = r.x; u < r.br().x; ++u)
      if (std::isfinite(d.at<float>(v, u))) valid.push_back(d.at<float>(v, u));
  if (valid.empty()) return {NAN, 0};
  std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
  return {valid[valid.size() / 2], double(valid.size()) / r.area()};
}

}  // namespace

TEST(StereoDisparity, SyntheticPairGivesKnownDisparities) {
  auto pair = test::syntheticPair();
  BlockHarness h("imagenets/StereoDisparity");
  h.set("num_disparities", 48);
  h.input("left", pair.output<sensor_msgs::Image>("left")).input("right", pair.output<sensor_msgs::Image>("right"));
  h.run();
  auto d = h.output<sensor_msgs::Image>("disparity");
  ASSERT_TRUE(d);
  EXPECT_EQ(d->encoding, "32FC1");
  // Wall (right part of the image, left of it is the band SGBM cannot match) and board centre.
  auto [wall, wall_valid] = medianIn(*d, cv::Rect(260, 20, 50, 200));
  auto [board, board_valid] = medianIn(*d, cv::Rect(140, 100, 40, 40));
  EXPECT_NEAR(wall, 12.0, 0.25);
  EXPECT_NEAR(board, 24.0, 0.25);
  EXPECT_GT(wall_valid, 0.9);
  EXPECT_GT(board_valid, 0.9);
  // The left band of num_disparities columns has no match: NaN, not 0.
  EXPECT_TRUE(std::isnan(medianIn(*d, cv::Rect(0, 0, 40, 240)).first));
}

TEST(StereoDisparity, KnownDepthThroughThePointCloud) {
  auto pair = test::syntheticPair();
  BlockHarness disparity("imagenets/StereoDisparity");
  disparity.set("num_disparities", 48);
  disparity.input("left", pair.output<sensor_msgs::Image>("left")).input("right", pair.output<sensor_msgs::Image>("right"));
  disparity.run();
  BlockHarness cloud("imagenets/DisparityToPointCloud");
  cloud.input("disparity", disparity.output<sensor_msgs::Image>("disparity"))
      .input("left_info", pair.output<sensor_msgs::CameraInfo>("left_info"))
      .input("right_info", pair.output<sensor_msgs::CameraInfo>("right_info"))
      .input("image", pair.output<sensor_msgs::Image>("left"));
  cloud.run();
  auto points = imagenets::cloud::readPoints(*cloud.output<sensor_msgs::PointCloud2>("cloud"));
  // Points on the board (|x|, |y| < 0.25 m): depth 1.25 m; elsewhere the wall at 2.5 m.
  std::vector<float> board_z, wall_z;
  for (const auto& p : points) {
    if (std::abs(p.x) < 0.25 && std::abs(p.y) < 0.25 && p.z < 2) board_z.push_back(p.z);
    if (std::abs(p.x) > 0.45 || std::abs(p.y) > 0.45) wall_z.push_back(p.z);
  }
  ASSERT_GT(board_z.size(), 3000u);
  ASSERT_GT(wall_z.size(), 10000u);
  std::nth_element(board_z.begin(), board_z.begin() + board_z.size() / 2, board_z.end());
  std::nth_element(wall_z.begin(), wall_z.begin() + wall_z.size() / 2, wall_z.end());
  EXPECT_NEAR(board_z[board_z.size() / 2], 1.25, 0.0125);  // 1 %
  EXPECT_NEAR(wall_z[wall_z.size() / 2], 2.5, 0.05);       // 2 % (a quarter pixel of 12)
}

TEST(StereoDisparity, MismatchedPairIsNamedError) {
  BlockHarness h("imagenets/StereoDisparity");
  h.input("left", toImageMsg(cv::Mat(240, 320, CV_8UC1), "mono8", std_msgs::Header()));
  h.input("right", toImageMsg(cv::Mat(240, 300, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("inputs 'left' (320x240) and 'right' (300x240) differ in size"), std::string::npos);
  h.input("right", toImageMsg(cv::Mat(240, 320, CV_8UC3), "bgr8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("differ in encoding"), std::string::npos);
  h.input("right", toImageMsg(cv::Mat(240, 320, CV_8UC1), "mono8", std_msgs::Header()));
  h.set("num_disparities", 40);
  EXPECT_NE(h.runError().find("property 'num_disparities': 40 is not a multiple of 16"), std::string::npos);
  h.set("num_disparities", 64);
  h.input("right", toImageMsg(cv::Mat(), "mono8", std_msgs::Header()));
  EXPECT_NE(h.runError().find("input 'right': empty image"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("disparity"));
}
