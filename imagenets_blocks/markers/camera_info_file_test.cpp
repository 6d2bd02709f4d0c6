#include <gtest/gtest.h>

#include <sensor_msgs/CameraInfo.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets;

namespace {
std::unique_ptr<Executor> cameraNet(const std::string& path) {
  const std::string yaml = "blocks:\n  camera: {type: imagenets/CameraInfoFile, properties: {path: " + path + "}}\n";
  return std::make_unique<Executor>(Net::build(parseNetText(yaml, "test", ".")), ExecutorOptions{1});
}
}  // namespace

TEST(CameraInfoFile, ReadsTheFriendStereoModels) {
  auto left = cameraNet("config/cameras/friend_stereo_left.yaml");
  ASSERT_TRUE(left->run().ok());
  const auto l = left->output<sensor_msgs::CameraInfo>("camera.camera_info");
  ASSERT_TRUE(l);
  EXPECT_EQ(l->width, 1024u);
  EXPECT_EQ(l->height, 768u);
  EXPECT_DOUBLE_EQ(l->K[0], 1400.0);
  EXPECT_EQ(l->D.size(), 5u);
  auto right = cameraNet("config/cameras/friend_stereo_right.yaml");
  ASSERT_TRUE(right->run().ok());
  const auto r = right->output<sensor_msgs::CameraInfo>("camera.camera_info");
  EXPECT_NEAR(-r->P[3] / r->P[0], 0.12, 1e-12);  // 120 mm baseline
}

TEST(CameraInfoFile, NamesAMissingFile) {
  auto exec = cameraNet("config/cameras/no_such_camera.yaml");
  const RunReport r = exec->run();
  ASSERT_EQ(r.failed.size(), 1u);
  EXPECT_NE(r.failed[0].find("no_such_camera.yaml"), std::string::npos) << r.failed[0];
}
