#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/vision/point_cloud.h"

using namespace imagenets::blocks;
using imagenets::cloud::PointXYZRGB;

TEST(PointCloudCrop, KeepsPointsInTheBox) {
  auto in = imagenets::cloud::makeCloud(
      {{0, 0, 1, 1, 2, 3}, {2, 0, 1, 4, 5, 6}, {0.5f, -0.5f, 4.9f, 7, 8, 9}, {0, 0, NAN, 0, 0, 0}}, true);
  BlockHarness h("imagenets/PointCloudCrop");
  h.input("cloud", in);
  h.run();
  auto kept = imagenets::cloud::readPoints(*h.output<sensor_msgs::PointCloud2>("cloud"));
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].g, 2);  // colour kept with the point
  EXPECT_FLOAT_EQ(kept[1].z, 4.9f);
  h.set("outside", true);
  h.run();
  ASSERT_EQ(imagenets::cloud::readPoints(*h.output<sensor_msgs::PointCloud2>("cloud")).size(), 1u);
  h.set("min", std::vector<double>{0, 0, 9});
  EXPECT_NE(h.runError().find("property 'min' exceeds 'max' on axis z"), std::string::npos);
  auto broken = imagenets::cloud::makeCloud({{0, 0, 1, 0, 0, 0}}, false);
  broken->fields[2].name = "depth";
  h.input("cloud", broken);
  EXPECT_NE(h.runError().find("input 'cloud': no FLOAT32 field 'z'"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("cloud"));
}
