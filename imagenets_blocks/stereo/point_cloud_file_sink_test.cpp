#include <cstring>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/testing/read_file.h"
#include "imagenets/vision/point_cloud.h"

using namespace imagenets::blocks;

TEST(PointCloudFileSink, WritesBinaryPly) {
  const auto path = (boost::filesystem::temp_directory_path() / boost::filesystem::unique_path("cloud-%%%%%%.ply")).string();
  BlockHarness h("imagenets/PointCloudFileSink");
  h.set("path", path).input("cloud", imagenets::cloud::makeCloud({{1, 2, 3, 10, 20, 30}, {4, 5, 6, 40, 50, 60}}, true));
  h.run();
  const std::string text = imagenets::testing::readFile(path);
  const auto end = text.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  EXPECT_NE(text.find("element vertex 2"), std::string::npos);
  EXPECT_NE(text.find("property uchar red"), std::string::npos);
  const std::string body = text.substr(end + 11);
  ASSERT_EQ(body.size(), 2u * 15);  // 3 floats + 3 bytes per point
  float x;
  std::memcpy(&x, body.data() + 15, 4);
  EXPECT_FLOAT_EQ(x, 4.0f);
  EXPECT_EQ(static_cast<uint8_t>(body[15 + 12]), 40);
  boost::filesystem::remove(path);
  h.set("path", "/nonexistent-dir/cloud.ply");
  EXPECT_NE(h.runError().find("cannot write '/nonexistent-dir/cloud.ply'"), std::string::npos);
  EXPECT_FALSE(boost::filesystem::exists("/nonexistent-dir/cloud.ply.tmp"));
}
