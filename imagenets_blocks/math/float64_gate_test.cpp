#include <gtest/gtest.h>

#include <cmath>

#include <std_msgs/Float64.h>

#include "imagenets/blocks/block_harness.h"
#include "number_test_util.h"

using namespace imagenets::blocks;
using imagenets::blocks::test::number;

namespace {
double gate(double value, double control, double min, double max) {
  BlockHarness h("imagenets/Float64Gate");
  h.set("min", min).set("max", max);
  h.input("value", number(value)).input("control", number(control));
  h.run();
  return h.output<std_msgs::Float64>("value")->data;
}
}  // namespace

TEST(Float64Gate, PassesTheValueOnlyWhileTheControlIsWithinBounds) {
  EXPECT_EQ(gate(0.93, 0.4, -1e9, 0.5), 0.93);
  EXPECT_EQ(gate(0.93, 0.5, -1e9, 0.5), 0.93);  // the bound itself passes
  EXPECT_TRUE(std::isnan(gate(0.93, 0.51, -1e9, 0.5)));
  EXPECT_TRUE(std::isnan(gate(0.93, 1.0, 2.0, 3.0)));  // below min
  EXPECT_TRUE(std::isnan(gate(0.93, std::nan(""), -1e9, 1e9)));
}
