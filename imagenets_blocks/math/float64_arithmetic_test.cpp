#include <gtest/gtest.h>

#include <cmath>

#include <std_msgs/Float64.h>

#include "imagenets/blocks/block_harness.h"
#include "number_test_util.h"

using namespace imagenets::blocks;
using imagenets::blocks::test::number;

namespace {
double compute(const std::string& op, double a, double b) {
  BlockHarness h("imagenets/Float64Arithmetic");
  h.set("operation", op);
  h.input("a", number(a)).input("b", number(b));
  h.run();
  return h.output<std_msgs::Float64>("result")->data;
}
}  // namespace

TEST(Float64Arithmetic, EveryOperation) {
  EXPECT_EQ(compute("add", 0.75, 0.5), 1.25);
  EXPECT_EQ(compute("subtract", 0.75, 0.5), 0.25);
  EXPECT_EQ(compute("multiply", 0.75, 0.5), 0.375);
  EXPECT_EQ(compute("divide", 0.75, 0.5), 1.5);
  EXPECT_EQ(compute("min", 0.75, 0.5), 0.5);
  EXPECT_EQ(compute("max", 0.75, 0.5), 0.75);
}

TEST(Float64Arithmetic, NaNPropagatesSoAnInvalidScoreStaysInvalid) {
  for (const char* op : {"add", "subtract", "multiply", "divide", "min", "max"}) {
    EXPECT_TRUE(std::isnan(compute(op, std::nan(""), 1.0))) << op;
    EXPECT_TRUE(std::isnan(compute(op, 1.0, std::nan("")))) << op;
  }
  EXPECT_TRUE(std::isinf(compute("divide", 1.0, 0.0)));
}

TEST(Float64Arithmetic, PropertyOperandWhenTheInputIsNotLinked) {
  BlockHarness h("imagenets/Float64Arithmetic");
  h.set("operation", std::string("multiply")).set("b", -0.1);
  h.input("a", number(2.0));
  h.run();
  EXPECT_DOUBLE_EQ(h.output<std_msgs::Float64>("result")->data, -0.2);
  EXPECT_THROW(h.set("operation", std::string("power")), imagenets::PropertyError);
}
