#include "imagenets/blocks/sub_net_port.h"

#include "imagenets/registry.h"

namespace imagenets {

template <NetPort::Direction D>
SubNetPort<D>::SubNetPort() {
  addProperty<std::string>("port", "", "name of the port on the outer SubNet block (default: this block's name)");
  addProperty<std::string>("type", "sensor_msgs/Image", "message type of the port, e.g. std_msgs/Float64");
  if (D == Direction::In) {
    addProperty<bool>("optional", false, "the outer block may run without a value here (e.g. a hint)");
  }
}

template <NetPort::Direction D>
void SubNetPort<D>::configure() {
  const PortType& port_type = netPortType(property<std::string>("type"));
  const bool in = D == Direction::In;
  addInput("value", port_type, in ? "set by the outer net" : "what the sub-net hands out");
  addOutput("value", port_type, in ? "the value, unchanged" : "the value, read by the outer SubNet block");
}

template class SubNetPort<NetPort::Direction::In>;
template class SubNetPort<NetPort::Direction::Out>;

}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::SubNetInput, "imagenets/SubNetInput", "sub-net", "Input port of a sub-net");
IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::SubNetOutput, "imagenets/SubNetOutput", "sub-net", "Output port of a sub-net");
IMAGENETS_REGISTER_BLOCK_FORMER_NAME("imagenets/ExecutorInput", "imagenets/SubNetInput");
IMAGENETS_REGISTER_BLOCK_FORMER_NAME("imagenets/ExecutorOutput", "imagenets/SubNetOutput");
