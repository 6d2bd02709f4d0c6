// A block that stands for a port of the net it sits in (paper 3.5): when that net runs as a block
// of another net (imagenets/SubNet), the outer block gets a port of this name and type. The
// outer block feeds an input port's `value` input, and reads an output port's `value` output.
// imagenets/SubNetInput and imagenets/SubNetOutput are the engine's own; any block library may
// add others, the sub-net block finds them through this interface, not by type name.
#pragma once

#include <string>
#include <vector>

namespace imagenets {

class Net;
class PortType;

class NetPort {
 public:
  enum class Direction { In, Out };
  virtual ~NetPort() = default;
  virtual Direction direction() const = 0;
  // The port's name on the outer block (after configure()); empty = the block's name in the net.
  virtual std::string outerName() const = 0;
  virtual const PortType& type() const = 0;
  // An input the outer block may run without (the sub-net's blocks fed by it then get no value).
  virtual bool optional() const { return false; }
};

// The port type a net port's `type` property names; throws PropertyError listing the known types.
const PortType& netPortType(const std::string& name);

// The node of `net` that is its port `name` (outer name) of `direction`, or -1: how a host finds
// what a net declares (e.g. its output `result`) without knowing its blocks.
int findNetPort(const Net& net, NetPort::Direction direction, const std::string& name);
// The port block of the node `node` of `net`, an index findNetPort gave (its type, optional()).
const NetPort& netPortAt(const Net& net, int node);
// The outer names of the net's ports of `direction`, in the net's order (for messages).
std::vector<std::string> netPortNames(const Net& net, NetPort::Direction direction);

}  // namespace imagenets
