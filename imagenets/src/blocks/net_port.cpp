#include "imagenets/net_port.h"

#include "imagenets/net.h"
#include "imagenets/port_type.h"
#include "imagenets/property.h"

namespace imagenets {

const PortType& netPortType(const std::string& name) {
  const PortType* type = PortType::find(name);
  if (!type) {
    std::string known;
    for (const auto& n : PortType::names()) known += (known.empty() ? "" : ", ") + n;
    throw PropertyError("property 'type': unknown message type '" + name + "' (known: " + known + ")");
  }
  return *type;
}

namespace {

// The port's name on an outer block: its `port`, else the block's name.
std::string outerName(const Net::Node& node, const NetPort& port) {
  const std::string name = port.outerName();
  return name.empty() ? node.name : name;
}

}  // namespace

int findNetPort(const Net& net, NetPort::Direction direction, const std::string& name) {
  for (size_t i = 0; i < net.nodes().size(); ++i) {
    const auto* port = dynamic_cast<const NetPort*>(net.nodes()[i].block.get());
    if (port && port->direction() == direction && outerName(net.nodes()[i], *port) == name) return static_cast<int>(i);
  }
  return -1;
}

const NetPort& netPortAt(const Net& net, int node) { return dynamic_cast<const NetPort&>(*net.node(node).block); }

std::vector<std::string> netPortNames(const Net& net, NetPort::Direction direction) {
  std::vector<std::string> names;
  for (const auto& node : net.nodes()) {
    const auto* port = dynamic_cast<const NetPort*>(node.block.get());
    if (port && port->direction() == direction) names.push_back(outerName(node, *port));
  }
  return names;
}

}  // namespace imagenets
