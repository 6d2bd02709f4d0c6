// A port's data type: a ROS message type, known by name ("sensor_msgs/Image"), with the few
// type-specific operations the engine and its hosts need. Values travel type-erased as
// boost::shared_ptr<const void>; a PortType turns them back into typed messages.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <boost/shared_ptr.hpp>
#include <ros/message_traits.h>
#include <ros/message_operations.h>
#include <ros/node_handle.h>
#include <ros/time.h>

namespace imagenets {

class PortType;

// One value on a port: an immutable message shared by every reader, never copied.
struct Value {
  const PortType* type = nullptr;
  boost::shared_ptr<const void> data;

  explicit operator bool() const { return static_cast<bool>(data); }
  template <class M>
  boost::shared_ptr<const M> as() const;  // null when empty; throws on a type mismatch
};

class PortType {
 public:
  using Callback = std::function<void(const Value&)>;

  std::string name;  // ROS data type, e.g. "sensor_msgs/Image"
  std::string md5;

  // Writes the message as YAML (ROS's message printer).
  std::function<void(std::ostream&, const Value&)> printYaml;
  // The header stamp, or ros::Time() for messages without a header.
  std::function<ros::Time(const Value&)> stamp;
  // Topic I/O for the nodelet host: messages pass by pointer inside one nodelet manager.
  std::function<ros::Subscriber(ros::NodeHandle&, const std::string& topic, uint32_t queue, Callback)>
      subscribe;
  std::function<ros::Publisher(ros::NodeHandle&, const std::string& topic, uint32_t queue, bool latch)>
      advertise;
  std::function<void(const ros::Publisher&, const Value&)> publish;

  // The PortType of message M, registered by name on first use.
  template <class M>
  static const PortType& of();
  // Look a type up by name ("sensor_msgs/Image"); null if no block or library registered it.
  static const PortType* find(const std::string& name);
  static std::vector<std::string> names();

  template <class M>
  Value wrap(const boost::shared_ptr<const M>& msg) const {
    return Value{this, msg};
  }

 private:
  static const PortType& registerType(std::unique_ptr<PortType> type);
};

template <class M>
const PortType& PortType::of() {
  static const PortType& type = []() -> const PortType& {
    auto t = std::make_unique<PortType>();
    t->name = ros::message_traits::DataType<M>::value();
    t->md5 = ros::message_traits::MD5Sum<M>::value();
    t->printYaml = [](std::ostream& os, const Value& v) {
      ros::message_operations::Printer<M>::stream(os, "", *static_cast<const M*>(v.data.get()));
    };
    t->stamp = [](const Value& v) -> ros::Time {
      if constexpr (ros::message_traits::HasHeader<M>::value) {
        return static_cast<const M*>(v.data.get())->header.stamp;
      } else {
        (void)v;
        return ros::Time();
      }
    };
    t->subscribe = [](ros::NodeHandle& nh, const std::string& topic, uint32_t queue, Callback cb) {
      const PortType* self = &PortType::of<M>();
      return nh.subscribe<M>(topic, queue, [cb, self](const boost::shared_ptr<const M>& msg) {
        cb(Value{self, msg});
      });
    };
    t->advertise = [](ros::NodeHandle& nh, const std::string& topic, uint32_t queue, bool latch) {
      return nh.advertise<M>(topic, queue, latch);
    };
    t->publish = [](const ros::Publisher& pub, const Value& v) {
      pub.publish(boost::static_pointer_cast<const M>(v.data));
    };
    return registerType(std::move(t));
  }();
  return type;
}

template <class M>
boost::shared_ptr<const M> Value::as() const {
  if (!data) return nullptr;
  const char* wanted = ros::message_traits::DataType<M>::value();  // no string built per read
  if (!type || type->name != wanted) {
    throw std::logic_error("value of type '" + (type ? type->name : std::string("?")) + "' read as '" +
                           wanted + "'");
  }
  return boost::static_pointer_cast<const M>(data);
}

}  // namespace imagenets
