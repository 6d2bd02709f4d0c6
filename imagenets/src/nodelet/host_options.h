// The nodelet host's own settings (pairing, queue_size, latch, source_mode, source_rate and, for a
// block running a net inside, publish_internal_ports). They are not block properties: the block
// never sees them. They are declared like properties only so that ROS parameters and
// dynamic_reconfigure load, check and change them the same way; a block property of the same
// name hides the host's. Settings that cannot change live are marked fixedAtLoad().
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imagenets/block.h"
#include "input_pairing.h"

namespace imagenets {

class HostOptions {
 public:
  HostOptions(const Block& block, bool inner_net);

  const std::vector<PropertySpec>& specs() const { return specs_; }  // the ones the block does not hide
  const PropertySpec* find(const std::string& name) const;
  const PropertyValues& values() const { return values_; }
  void set(const std::string& name, const PropertyValue& value);  // validated; throws PropertyError

  PairingOptions pairing() const;
  uint32_t queueSize() const { return static_cast<uint32_t>(std::get<int>(value("queue_size"))); }
  bool latch() const { return std::get<bool>(value("latch")); }
  std::string sourceMode() const { return std::get<std::string>(value("source_mode")); }
  double sourceRate() const { return std::get<double>(value("source_rate")); }
  bool publishInternalPorts() const;

 private:
  // The value, or the default of a setting the block hides.
  PropertyValue value(const std::string& name) const;
  std::vector<PropertySpec> specs_;
  std::vector<PropertySpec> hidden_;
  PropertyValues values_;
};

}  // namespace imagenets
