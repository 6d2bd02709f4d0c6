#include <gtest/gtest.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Float64MultiArray.h>

#include "imagenets/blocks/block_harness.h"

using namespace imagenets::blocks;

TEST(PlotSeries, PlotsOverIndexOrX) {
  std_msgs::Float64MultiArray::Ptr y(new std_msgs::Float64MultiArray), x(new std_msgs::Float64MultiArray);
  y->data = {3, 1, 4, 1, 5};
  BlockHarness h("imagenets/PlotSeries");
  h.set("width", 300).set("height", 160).input("y", y);
  h.run();
  auto img = h.output<sensor_msgs::Image>("image");
  ASSERT_TRUE(img);
  EXPECT_EQ(img->width, 300u);
  x->data = {0, 1, 2};
  h.input("x", x);
  EXPECT_NE(h.runError().find("inputs 'x' (3 values) and 'y' (5 values) differ in length"), std::string::npos);
  EXPECT_FALSE(h.hasOutput("image"));
  y->data.clear();
  h.clear("x");
  EXPECT_NE(h.runError().find("input 'y': empty array"), std::string::npos);
}
