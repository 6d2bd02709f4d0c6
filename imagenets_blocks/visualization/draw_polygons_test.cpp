#include <gtest/gtest.h>
#include <imagenets/Polygons.h>

#include "imagenets/blocks/block_harness.h"
#include "imagenets/blocks/image.h"

using namespace imagenets::blocks;

TEST(DrawPolygons, DrawsOutlineInColourOnGray) {
  imagenets::Polygons::Ptr polys(new imagenets::Polygons);
  geometry_msgs::Polygon square;
  for (auto [x, y] : {std::pair{10, 10}, {30, 10}, {30, 30}, {10, 30}}) {
    geometry_msgs::Point32 p;
    p.x = x;
    p.y = y;
    square.points.push_back(p);
  }
  polys->polygons.push_back(square);
  BlockHarness h("imagenets/DrawPolygons");
  h.set("colour", std::vector<double>{0, 0, 255}).set("thickness", 1);
  h.input("image", toImageMsg(cv::Mat(40, 40, CV_8UC1, cv::Scalar(0)), "mono8", std_msgs::Header()));
  h.input("polygons", polys);
  h.run();
  auto out = h.output<sensor_msgs::Image>("image");
  ASSERT_EQ(out->encoding, "bgr8");
  auto px = [&](int r, int c) { return cv::Vec3b(&out->data[r * out->step + 3 * c]); };
  EXPECT_GT(px(10, 20)[2], 200);  // on the top edge: red
  EXPECT_EQ(px(10, 20)[1], 0);
  EXPECT_EQ(px(20, 20), cv::Vec3b(0, 0, 0));  // inside: untouched
  EXPECT_GT(px(20, 30)[2], 200);  // right edge
  h.set("colour", std::vector<double>{1, 2});
  EXPECT_NE(h.runError().find("property 'colour': 2 values"), std::string::npos);
  h.clear("polygons");
  EXPECT_EQ(h.runError(), "input 'polygons' has no value");
}
