#include <fstream>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/block_harness.h"

using namespace imagenets::blocks;

namespace {
// A camera-info file as camera_calibration writes it.
const char* kYaml = R"(image_width: 1024
image_height: 768
camera_name: left
camera_matrix:
  rows: 3
  cols: 3
  data: [800, 0, 511.5, 0, 805, 383.5, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.1, 0.01, 0, 0, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [800, 0, 511.5, -96, 0, 805, 383.5, 0, 0, 0, 1, 0]
)";

std::string writeTemp(const std::string& text) {
  const auto path = boost::filesystem::temp_directory_path() / boost::filesystem::unique_path("caminfo-%%%%%%.yaml");
  std::ofstream(path.string()) << text;
  return path.string();
}
}  // namespace

TEST(CameraInfoFile, ReadsStandardYaml) {
  const std::string path = writeTemp(kYaml);
  BlockHarness h("imagenets/CameraInfoFile");
  h.set("path", path).set("frame_id", "left_optical");
  h.run();
  auto info = h.output<sensor_msgs::CameraInfo>("camera_info");
  ASSERT_TRUE(info);
  EXPECT_EQ(info->width, 1024u);
  EXPECT_EQ(info->height, 768u);
  EXPECT_EQ(info->header.frame_id, "left_optical");
  EXPECT_EQ(info->distortion_model, "plumb_bob");
  EXPECT_DOUBLE_EQ(info->K[4], 805);
  EXPECT_DOUBLE_EQ(info->D[0], -0.1);
  EXPECT_DOUBLE_EQ(info->P[3], -96);
  boost::filesystem::remove(path);
}

TEST(CameraInfoFile, MissingOrBrokenFileIsNamedError) {
  BlockHarness h("imagenets/CameraInfoFile");
  h.set("path", "/nonexistent/left.yaml");
  EXPECT_NE(h.runError().find("cannot read a camera model from '/nonexistent/left.yaml'"), std::string::npos)
      << h.runError();
  const std::string path = writeTemp("image_width: 0\nimage_height: 0\n");
  h.set("path", path);
  EXPECT_NE(h.runError(), "");
  EXPECT_FALSE(h.hasOutput("camera_info"));
  boost::filesystem::remove(path);
}
