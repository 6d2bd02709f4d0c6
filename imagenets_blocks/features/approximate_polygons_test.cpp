#include <gtest/gtest.h>
#include <imagenets/Polygons.h>

#include "imagenets/blocks/block_harness.h"

using namespace imagenets::blocks;

TEST(ApproximatePolygons, DenseSquareBecomesFourCorners) {
  imagenets::Polygons::Ptr in(new imagenets::Polygons);
  geometry_msgs::Polygon square;
  const float corners[4][2] = {{10, 10}, {50, 10}, {50, 50}, {10, 50}};
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < 40; ++k) {
      geometry_msgs::Point32 p;
      const float t = k / 40.0f;
      p.x = corners[side][0] + t * (corners[(side + 1) % 4][0] - corners[side][0]) + ((k % 2) ? 0.3f : -0.3f);
      p.y = corners[side][1] + t * (corners[(side + 1) % 4][1] - corners[side][1]);
      square.points.push_back(p);
    }
  }
  in->polygons.push_back(square);
  BlockHarness h("imagenets/ApproximatePolygons");
  h.input("contours", in);
  h.run();
  auto out = h.output<imagenets::Polygons>("polygons");
  ASSERT_EQ(out->polygons.size(), 1u);
  ASSERT_EQ(out->polygons[0].points.size(), 4u);
  for (const auto& p : out->polygons[0].points) {
    bool near_corner = false;
    for (const auto& c : corners) near_corner = near_corner || (std::abs(p.x - c[0]) < 1 && std::abs(p.y - c[1]) < 1);
    EXPECT_TRUE(near_corner) << p.x << "," << p.y;
  }
  in->polygons[0].points[3].x = std::nanf("");
  EXPECT_NE(h.runError().find("input 'contours': polygon 0 has a vertex that is not finite"), std::string::npos);
}
