// Collectors of repeated results (collectors.h): the engine's own (numbers), and any library's.
#include <gtest/gtest.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <std_msgs/String.h>

#include "imagenets/collectors.h"

using namespace imagenets;

namespace {

// A library's own collector, as any block library would add one.
CollectorRegistration<std_msgs::String, std_msgs::String> joined_words(
    [](const std::vector<std_msgs::String::ConstPtr>& items) {
      auto out = boost::make_shared<std_msgs::String>();
      for (const auto& item : items) out->data += (out->data.empty() ? "" : " ") + item->data;
      return out;
    });

template <class M>
Value wrap(boost::shared_ptr<M> msg) {
  return PortType::of<M>().wrap(boost::shared_ptr<const M>(msg));
}

}  // namespace

TEST(Collectors, NumbersBecomeAnArrayInOrder) {
  const Collector* c = Collectors::find(PortType::of<std_msgs::Float64>());
  ASSERT_TRUE(c);
  EXPECT_EQ(c->collection->name, "std_msgs/Float64MultiArray");
  std::vector<Value> values;
  for (double v : {3.0, 1.0, 2.0}) {
    auto m = boost::make_shared<std_msgs::Float64>();
    m->data = v;
    values.push_back(wrap(m));
  }
  auto array = c->collect(values).as<std_msgs::Float64MultiArray>();
  ASSERT_TRUE(array);
  EXPECT_EQ(array->data, (std::vector<double>{3, 1, 2}));
  EXPECT_EQ(array->layout.dim[0].label, "repetition");
}

TEST(Collectors, ALibraryAddsItsOwnAndTypesWithoutOneHaveNone) {
  const Collector* c = Collectors::find(PortType::of<std_msgs::String>());
  ASSERT_TRUE(c);
  std::vector<Value> values;
  for (const char* w : {"one", "two"}) {
    auto m = boost::make_shared<std_msgs::String>();
    m->data = w;
    values.push_back(wrap(m));
  }
  EXPECT_EQ(c->collect(values).as<std_msgs::String>()->data, "one two");
  EXPECT_FALSE(Collectors::find(PortType::of<std_msgs::Float64MultiArray>()));
}
