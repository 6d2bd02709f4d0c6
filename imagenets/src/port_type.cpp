#include "imagenets/port_type.h"

#include <map>
#include <mutex>

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Bool.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>

namespace imagenets {
namespace {

struct TypeTable {
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<PortType>> by_name;
};

TypeTable& table() {
  static TypeTable t;
  return t;
}

// The common types are known by name from the start, so a net can name them (e.g. the message
// type of a sub-net's input) before any block that uses them was created.
const bool common_types_registered = [] {
  PortType::of<sensor_msgs::Image>();
  PortType::of<sensor_msgs::CameraInfo>();
  PortType::of<sensor_msgs::JointState>();
  PortType::of<sensor_msgs::PointCloud2>();
  PortType::of<geometry_msgs::TransformStamped>();
  PortType::of<geometry_msgs::PoseStamped>();
  PortType::of<geometry_msgs::PoseArray>();
  PortType::of<std_msgs::Float64>();
  PortType::of<std_msgs::Float64MultiArray>();
  PortType::of<std_msgs::Int32>();
  PortType::of<std_msgs::Bool>();
  PortType::of<std_msgs::String>();
  return true;
}();

}  // namespace

const PortType& PortType::registerType(std::unique_ptr<PortType> type) {
  TypeTable& t = table();
  std::lock_guard<std::mutex> lock(t.mutex);
  auto it = t.by_name.find(type->name);
  if (it != t.by_name.end()) return *it->second;  // a second shared object may register again
  const PortType& ref = *type;
  t.by_name.emplace(type->name, std::move(type));
  return ref;
}

const PortType* PortType::find(const std::string& name) {
  (void)common_types_registered;
  TypeTable& t = table();
  std::lock_guard<std::mutex> lock(t.mutex);
  auto it = t.by_name.find(name);
  return it == t.by_name.end() ? nullptr : it->second.get();
}

std::vector<std::string> PortType::names() {
  (void)common_types_registered;
  TypeTable& t = table();
  std::lock_guard<std::mutex> lock(t.mutex);
  std::vector<std::string> out;
  for (const auto& kv : t.by_name) out.push_back(kv.first);
  return out;
}

}  // namespace imagenets
