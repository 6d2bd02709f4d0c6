// imagenets/SubNetInput and imagenets/SubNetOutput: the ports of a sub-net (paper 3.5). Each
// becomes a port of the outer imagenets/SubNet block: the outer block feeds an input's `value`,
// and reads an output's `value`; the value passes through unchanged (same pointer).
#pragma once

#include "imagenets/block.h"
#include "imagenets/net_port.h"

namespace imagenets {

template <NetPort::Direction D>
class SubNetPort : public Block, public NetPort {
 public:
  SubNetPort();
  void configure() override;
  void process(Context& ctx) override { ctx.setOutput("value", ctx.inputValue("value")); }

  Direction direction() const override { return D; }
  std::string outerName() const override { return property<std::string>("port"); }
  const PortType& type() const override { return *inputs().front().type; }
  bool optional() const override { return D == Direction::In && property<bool>("optional"); }
};

using SubNetInput = SubNetPort<NetPort::Direction::In>;
using SubNetOutput = SubNetPort<NetPort::Direction::Out>;

}  // namespace imagenets
