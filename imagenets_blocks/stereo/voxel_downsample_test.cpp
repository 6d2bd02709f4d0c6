#include <gtest/gtest.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/vision/point_cloud.h"

using namespace imagenets::blocks;

TEST(VoxelDownsample, CentroidPerVoxel) {
  // Two points in voxel [0,1)^3, one in [1,2)x[0,1)x[0,1) with leaf 1 m.
  auto in = imagenets::cloud::makeCloud({{0.2f, 0.2f, 0.2f, 100, 0, 0}, {0.6f, 0.4f, 0.8f, 200, 0, 0}, {1.5f, 0.5f, 0.5f, 0, 50, 0}},
                                        true);
  BlockHarness h("imagenets/VoxelDownsample");
  h.set("leaf_size", 1.0).input("cloud", in);
  h.run();
  auto out = imagenets::cloud::readPoints(*h.output<sensor_msgs::PointCloud2>("cloud"));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[0].x, 0.4f);
  EXPECT_FLOAT_EQ(out[0].z, 0.5f);
  EXPECT_EQ(out[0].r, 150);
  EXPECT_FLOAT_EQ(out[1].x, 1.5f);
  h.set("min_points", 2);
  h.run();
  EXPECT_EQ(imagenets::cloud::readPoints(*h.output<sensor_msgs::PointCloud2>("cloud")).size(), 1u);
  h.clear("cloud");
  EXPECT_EQ(h.runError(), "input 'cloud' has no value");
}
