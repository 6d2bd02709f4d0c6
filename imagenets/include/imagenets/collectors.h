// Collections of repeated results: a sub-net run N times (imagenets/SubNet, `repeat: N`) also
// hands out, beside each output, its N results as one message (`<port>_all`) when a collector is
// registered for the output's type. Any block library adds collectors for its own types:
//
//   static imagenets::CollectorRegistration<std_msgs::Float64, std_msgs::Float64MultiArray> numbers(
//       [](const std::vector<std_msgs::Float64::ConstPtr>& items) { ... return array; });
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "imagenets/port_type.h"

namespace imagenets {

struct Collector {
  const PortType* item = nullptr;        // e.g. std_msgs/Float64
  const PortType* collection = nullptr;  // e.g. std_msgs/Float64MultiArray
  std::function<Value(const std::vector<Value>&)> collect;  // items of type `item`, none empty
};

class Collectors {
 public:
  // The first collector registered for a type wins (a library loaded twice registers again).
  static void add(Collector collector);
  static const Collector* find(const PortType& item);  // null if none
};

template <class Item, class Collection>
struct CollectorRegistration {
  using Collect = std::function<boost::shared_ptr<Collection>(const std::vector<boost::shared_ptr<const Item>>&)>;
  explicit CollectorRegistration(Collect collect) {
    Collectors::add(Collector{&PortType::of<Item>(), &PortType::of<Collection>(), [collect](const std::vector<Value>& values) {
                                std::vector<boost::shared_ptr<const Item>> items;
                                for (const Value& v : values) items.push_back(v.as<Item>());
                                return PortType::of<Collection>().wrap(boost::shared_ptr<const Collection>(collect(items)));
                              }});
  }
};

}  // namespace imagenets
