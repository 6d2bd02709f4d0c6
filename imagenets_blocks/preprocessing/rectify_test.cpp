#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

namespace {

const double kFx = 300, kFy = 300, kCx = 160, kCy = 120;

sensor_msgs::CameraInfo::Ptr model(std::vector<double> d) {
  sensor_msgs::CameraInfo::Ptr info(new sensor_msgs::CameraInfo);
  info->width = 320;
  info->height = 240;
  info->distortion_model = "plumb_bob";
  info->D = std::move(d);
  info->K = {kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1};
  info->R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info->P = {kFx, 0, kCx, 0, 0, kFy, kCy, 0, 0, 0, 1, 0};
  return info;
}

// Intensity-weighted centroid of the pixels above half the maximum.
cv::Point2d centroid(const cv::Mat& img) {
  double max = 0;
  cv::minMaxLoc(img, nullptr, &max);
  cv::Mat mask = img > max / 2;
  const cv::Moments m = cv::moments(mask & img, false);
  return {m.m10 / m.m00, m.m01 / m.m00};
}

}  // namespace

TEST(Rectify, UndoesRadialDistortionOfAKnownPoint) {
  // A 3D point seen through a barrel-distorted lens: its raw image position comes from
  // cv::projectPoints with D; after rectification it must sit at the ideal pinhole position.
  const std::vector<double> d{-0.25, 0.05, 0, 0, 0};
  const cv::Point3d point(0.42, -0.3, 1.0);
  std::vector<cv::Point2d> distorted;
  cv::projectPoints(std::vector<cv::Point3d>{point}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                    cv::Matx33d(kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1), d, distorted);
  const cv::Point2d ideal(kCx + kFx * point.x / point.z, kCy + kFy * point.y / point.z);
  ASSERT_GT(cv::norm(distorted[0] - ideal), 8.0);  // the distortion is visible

  // A small Gaussian spot at the distorted position.
  cv::Mat raw(240, 320, CV_8UC1);
  for (int r = 0; r < raw.rows; ++r)
    for (int c = 0; c < raw.cols; ++c) {
      const double dx = c - distorted[0].x, dy = r - distorted[0].y;
      raw.at<uchar>(r, c) = cv::saturate_cast<uchar>(250 * std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5)));
    }
  BlockHarness h("imagenets/Rectify");
  h.input("image", toImageMsg(raw, "mono8", std_msgs::Header())).input("camera_info", model(d));
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(out);
  const cv::Mat rectified(240, 320, CV_8UC1, const_cast<uint8_t*>(out->data.data()), out->step);
  EXPECT_LT(cv::norm(centroid(rectified) - ideal), 0.3) << centroid(rectified) << " vs " << ideal;
  auto info = h.output<sensor_msgs::CameraInfo>("camera_info");
  EXPECT_DOUBLE_EQ(info->D[0], 0);
  EXPECT_DOUBLE_EQ(info->K[2], kCx);
}

TEST(Rectify, MissingOrMismatchedModelIsNamedError) {
  BlockHarness h("imagenets/Rectify");
  h.input("image", toImageMsg(cv::Mat(120, 160, CV_8UC1), "mono8", std_msgs::Header()));
  EXPECT_EQ(h.runError(), "input 'camera_info' has no value");
  h.input("camera_info", model({0, 0, 0, 0, 0}));
  EXPECT_NE(h.runError().find("input 'camera_info' is for 320x240 images, input 'image' is 160x120"), std::string::npos);
  auto uncalibrated = model({});
  uncalibrated->K = {};
  h.input("image", toImageMsg(cv::Mat(240, 320, CV_8UC1), "mono8", std_msgs::Header())).input("camera_info", uncalibrated);
  EXPECT_NE(h.runError().find("K has no focal length"), std::string::npos);
  h.input("image", toImageMsg(cv::Mat(240, 320, CV_32FC1), "32FC1", std_msgs::Header()));
  EXPECT_NE(h.runError().find("encoding '32FC1' not accepted"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
}
