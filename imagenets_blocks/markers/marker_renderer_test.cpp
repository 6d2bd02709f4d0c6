// The marker image generator of Fig. 5.1 as a net: image, camera_info and the true pose.
#include <gtest/gtest.h>

#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/executor.h"

using namespace imagenets;

TEST(MarkerRenderer, GeneratesTheImageAndItsGroundTruth) {
  auto exec = Executor::loadFile("config/nets/marker_image_generation.yaml", ExecutorOptions{1});
  exec->setProperty("render", "supersampling", 2);
  exec->setProperty("render", "tilt", 50.0);
  const RunReport report = exec->run();
  ASSERT_TRUE(report.ok());
  const auto image = exec->output<sensor_msgs::Image>("render.image");
  ASSERT_TRUE(image);
  EXPECT_EQ(image->width, 1024u);
  EXPECT_EQ(image->height, 768u);
  EXPECT_EQ(image->encoding, "mono8");
  const auto truth = exec->output<geometry_msgs::PoseStamped>("render.ground_truth");
  ASSERT_TRUE(truth);
  const Eigen::Isometry3d expected = render::lookAtOriginPose(0.6, 270 * M_PI / 180, 50 * M_PI / 180);
  const Eigen::Isometry3d got = marker::fromPoseMsg(truth->pose);
  EXPECT_LT((got.translation() - expected.translation()).norm(), 1e-9);
  EXPECT_LT(marker::rotationAngle(got, expected), 1e-6);
  EXPECT_EQ(truth->header.frame_id, "friend_stereo_left_optical_frame");
  ASSERT_TRUE(exec->output<sensor_msgs::CameraInfo>("render.camera_info"));

  exec->setPropertyText("render", "light_direction", "[1, 0]");
  const RunReport bad = exec->run();
  ASSERT_EQ(bad.failed.size(), 1u);
  EXPECT_NE(bad.failed[0].find("light_direction"), std::string::npos) << bad.failed[0];
}
