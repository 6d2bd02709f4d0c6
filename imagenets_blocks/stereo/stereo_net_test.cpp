// The shipped stereo net (config/nets/stereo_point_cloud.yaml) end to end: files -> rectify ->
// SGBM -> cloud, with the depths of the shipped synthetic pair; and a broken input stops the
// blocks downstream of it.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <sensor_msgs/PointCloud2.h>

#include "imagenets/vision/point_cloud.h"
#include "imagenets/executor.h"

namespace {
float median(std::vector<float> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}
}  // namespace

TEST(StereoNet, ShippedPairGivesKnownDepths) {
  auto exec = imagenets::Executor::loadFile("config/nets/stereo_point_cloud.yaml", {2});
  const imagenets::RunReport report = exec->run();
  ASSERT_TRUE(report.ok()) << (report.failed.empty() ? "" : report.failed[0]);
  auto cloud = exec->output<sensor_msgs::PointCloud2>("cloud.cloud");
  ASSERT_TRUE(cloud);
  EXPECT_EQ(cloud->header.frame_id, "left_camera_optical");
  std::vector<float> board, wall;
  for (const auto& p : imagenets::cloud::readPoints(*cloud)) {
    if (std::abs(p.x) < 0.3 && std::abs(p.y) < 0.3 && p.z < 2.2) board.push_back(p.z);  // board: 0.8 m at 1.5 m
    if (std::abs(p.x) > 0.6 || std::abs(p.y) > 0.6) wall.push_back(p.z);                // wall at 3 m
  }
  ASSERT_GT(board.size(), 20000u);
  ASSERT_GT(wall.size(), 50000u);
  EXPECT_NEAR(median(board), 1.5, 0.015);
  EXPECT_NEAR(median(wall), 3.0, 0.06);
  EXPECT_TRUE(exec->output<sensor_msgs::PointCloud2>("downsample.cloud"));
}

TEST(StereoNet, MissingCameraModelStopsEverythingDownstream) {
  auto exec = imagenets::Executor::loadFile("config/nets/stereo_point_cloud.yaml", {2});
  ASSERT_TRUE(exec->run().ok());  // a good run first: its outputs must not linger after the failure
  exec->setProperty("right_model", "path", std::string("/nonexistent/right.yaml"));
  const imagenets::RunReport report = exec->run();
  ASSERT_EQ(report.failed.size(), 1u);
  EXPECT_NE(report.failed[0].find("right_model"), std::string::npos);
  EXPECT_NE(report.failed[0].find("cannot read a camera model from '/nonexistent/right.yaml'"), std::string::npos)
      << report.failed[0];
  for (const char* port : {"rectify_right.image", "disparity.disparity", "cloud.cloud", "downsample.cloud"}) {
    EXPECT_FALSE(static_cast<bool>(exec->output(port))) << port;
  }
  EXPECT_TRUE(static_cast<bool>(exec->output("rectify_left.image")));  // the other branch is unaffected
}
