#include "imagenets/collectors.h"

#include <memory>
#include <mutex>

#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>

namespace imagenets {
namespace {

std::mutex& registryMutex() {
  static std::mutex mutex;
  return mutex;
}
std::vector<std::unique_ptr<Collector>>& registry() {
  static std::vector<std::unique_ptr<Collector>> collectors;
  return collectors;
}

// Numbers (scores, distances) become one array, in repetition order: the engine's own type.
CollectorRegistration<std_msgs::Float64, std_msgs::Float64MultiArray> numbers(
    [](const std::vector<std_msgs::Float64::ConstPtr>& items) {
      auto array = boost::make_shared<std_msgs::Float64MultiArray>();
      for (const auto& item : items) array->data.push_back(item->data);
      array->layout.dim.resize(1);
      array->layout.dim[0].label = "repetition";
      array->layout.dim[0].size = array->layout.dim[0].stride = array->data.size();
      return array;
    });

}  // namespace

void Collectors::add(Collector collector) {
  std::lock_guard<std::mutex> lock(registryMutex());
  for (const auto& known : registry()) {
    if (known->item == collector.item) return;
  }
  registry().push_back(std::make_unique<Collector>(std::move(collector)));
}

const Collector* Collectors::find(const PortType& item) {
  std::lock_guard<std::mutex> lock(registryMutex());
  for (const auto& known : registry()) {
    if (known->item == &item) return known.get();
  }
  return nullptr;
}

}  // namespace imagenets
