// The nodelet host's stamp pairing, without ROS: which input sets make a block run.
#include <optional>

#include <boost/weak_ptr.hpp>
#include <gtest/gtest.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Float64.h>

#include "../../src/nodelet/input_pairing.h"

namespace imagenets {
namespace {

Value image(double stamp) {
  auto m = boost::make_shared<sensor_msgs::Image>();
  m->header.stamp = ros::Time(stamp);
  return PortType::of<sensor_msgs::Image>().wrap(sensor_msgs::ImageConstPtr(m));
}
Value number(double v) {
  auto m = boost::make_shared<std_msgs::Float64>();
  m->data = v;
  return PortType::of<std_msgs::Float64>().wrap(std_msgs::Float64ConstPtr(m));
}
double stampOf(const Value& v) { return v.as<sensor_msgs::Image>()->header.stamp.toSec(); }

// The input set the arrival completes, if any.
std::optional<std::vector<Value>> add(InputPairing& pairing, size_t input, const Value& value) {
  std::vector<Value> set;
  if (!pairing.add(input, value, &set)) return std::nullopt;
  return set;
}

TEST(InputPairing, ExactPairsOnlyEqualStampsAndReusesKeptMessages) {
  InputPairing pairing({true, true}, PairingOptions{});
  EXPECT_FALSE(add(pairing, 0, image(1.0)));
  EXPECT_FALSE(add(pairing, 1, image(2.0)));
  auto set = add(pairing, 1, image(1.0));
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[0]), 1.0);
  EXPECT_EQ(stampOf((*set)[1]), 1.0);
  // Input 0 re-published for stamp 2 (a property changed upstream): pairs with the kept b@2.
  set = add(pairing, 0, image(2.0));
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[1]), 2.0);
}

TEST(InputPairing, ApproximatePairsTheClosestWithinTheSlop) {
  PairingOptions options;
  options.approximate = true;
  options.slop = 0.1;
  InputPairing pairing({true, true}, options);
  add(pairing, 1, image(9.95));
  add(pairing, 1, image(10.08));
  auto set = add(pairing, 0, image(10.0));
  ASSERT_TRUE(set);
  EXPECT_DOUBLE_EQ(stampOf((*set)[1]), 9.95);  // 0.05 beats 0.08
  EXPECT_FALSE(add(pairing, 0, image(10.5)));
}

TEST(InputPairing, HeaderlessInputsJoinWithTheirLatestValue) {
  InputPairing pairing({true, true}, PairingOptions{});
  EXPECT_FALSE(add(pairing, 1, number(5.0)));  // nothing stamped yet on input 0
  auto set = add(pairing, 0, image(3.0));
  ASSERT_TRUE(set);
  EXPECT_EQ((*set)[1].as<std_msgs::Float64>()->data, 5.0);
  set = add(pairing, 1, number(6.0));  // re-runs with the newest stamped message
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[0]), 3.0);
}

TEST(InputPairing, OptionalInputsDoNotHoldARunBack) {
  InputPairing pairing({true, false}, PairingOptions{});
  auto set = add(pairing, 0, image(1.0));
  ASSERT_TRUE(set);
  EXPECT_FALSE((*set)[1]);
  add(pairing, 1, image(7.0));
  set = add(pairing, 0, image(2.0));
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[1]), 7.0);  // no stamp match: the latest value
}

TEST(InputPairing, ASourceRunsOnlyOnDemandButKeepsItsInputs) {
  InputPairing pairing({false}, PairingOptions{}, true);
  EXPECT_TRUE(pairing.isSource());
  EXPECT_FALSE(add(pairing, 0, image(1.0)));
  EXPECT_EQ(stampOf(pairing.latest()[0]), 1.0);
}

TEST(InputPairing, AllOptionalInputsRunOnEveryArrival) {
  InputPairing pairing({false, false}, PairingOptions{});
  auto set = add(pairing, 0, image(1.0));
  ASSERT_TRUE(set);
  EXPECT_FALSE((*set)[1]);
  set = add(pairing, 1, image(1.0));
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[0]), 1.0);
}

TEST(InputPairing, KeepsOnlyTheHistoryAskedFor) {
  PairingOptions options;
  options.history = 2;
  InputPairing pairing({true, true}, options);
  add(pairing, 1, image(1.0));
  add(pairing, 1, image(2.0));
  add(pairing, 1, image(3.0));
  EXPECT_FALSE(add(pairing, 0, image(1.0)));  // b@1 was dropped
  EXPECT_TRUE(add(pairing, 0, image(2.0)));
}

TEST(InputPairing, ASingleInputHoldsOnlyItsNewestMessage) {
  // Nothing pairs with it, so older images are let go at once whatever the history asked for.
  PairingOptions options;
  options.history = 5;
  InputPairing pairing({true}, options);
  Value first = image(1.0);
  const boost::weak_ptr<const void> held = first.data;
  EXPECT_TRUE(add(pairing, 0, first));
  first = Value();
  EXPECT_FALSE(held.expired());
  const auto set = add(pairing, 0, image(2.0));
  ASSERT_TRUE(set);
  EXPECT_EQ(stampOf((*set)[0]), 2.0);
  EXPECT_TRUE(held.expired());
  EXPECT_EQ(stampOf(pairing.latest()[0]), 2.0);
}

}  // namespace
}  // namespace imagenets
