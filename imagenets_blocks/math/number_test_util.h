// Message builder for the math block tests.
#pragma once

#include <std_msgs/Float64.h>

namespace imagenets {
namespace blocks {
namespace test {

inline boost::shared_ptr<std_msgs::Float64> number(double v) {
  auto m = boost::make_shared<std_msgs::Float64>();
  m->data = v;
  return m;
}

}  // namespace test
}  // namespace blocks
}  // namespace imagenets
