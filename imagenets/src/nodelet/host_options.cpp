#include "host_options.h"

namespace imagenets {

HostOptions::HostOptions(const Block& block, bool inner_net) {
  std::vector<PropertySpec> all;
  all.emplace_back("pairing", PropertyKind::String, std::string("exact"),
                   "how several inputs are paired by header stamp: exact or approximate (within pairing_slop)");
  all.back().choices({"exact", "approximate"});
  all.emplace_back("pairing_slop", PropertyKind::Double, 0.05, "largest stamp difference (s) paired in approximate mode");
  all.back().range(0.0, 3600.0);
  all.emplace_back("queue_size", PropertyKind::Int, 5,
                   "messages kept per input (subscriber queue and pairing); load time only");
  all.back().range(1, 1000).fixedAtLoad();
  all.emplace_back("latch", PropertyKind::Bool, false,
                   "latch the outputs (late subscribers get the last value; costs one serialisation per message); "
                   "outputs of a source run `once` are always latched; load time only");
  all.back().fixedAtLoad();
  all.emplace_back("source_mode", PropertyKind::String, std::string("timer"),
                   "a source (a block without required or linked inputs) runs: once (at load), timer (every "
                   "1/source_rate s) or trigger (on ~run only)");
  all.back().choices({"once", "timer", "trigger"});
  all.emplace_back("source_rate", PropertyKind::Double, 1.0, "runs per second of a source in timer mode");
  all.back().range(0.001, 1000.0);
  if (inner_net) {
    all.emplace_back("publish_internal_ports", PropertyKind::Bool, false,
                     "publish every output port of the inner net as ~internal/<block>/<port>, only while subscribed");
  }
  for (PropertySpec& spec : all) {
    (block.findProperty(spec.name()) ? hidden_ : specs_).push_back(spec);
    if (!block.findProperty(spec.name())) values_[spec.name()] = spec.defaultValue();
  }
}

const PropertySpec* HostOptions::find(const std::string& name) const {
  for (const PropertySpec& s : specs_) {
    if (s.name() == name) return &s;
  }
  return nullptr;
}

void HostOptions::set(const std::string& name, const PropertyValue& value) {
  const PropertySpec* spec = find(name);
  if (!spec) throw PropertyError("unknown property '" + name + "'");
  values_[name] = spec->validate(value);
}

PropertyValue HostOptions::value(const std::string& name) const {
  auto it = values_.find(name);
  if (it != values_.end()) return it->second;
  for (const PropertySpec& s : hidden_) {
    if (s.name() == name) return s.defaultValue();
  }
  throw std::logic_error("no host option '" + name + "'");
}

PairingOptions HostOptions::pairing() const {
  PairingOptions o;
  o.approximate = std::get<std::string>(value("pairing")) == "approximate";
  o.slop = std::get<double>(value("pairing_slop"));
  o.history = queueSize();
  return o;
}

bool HostOptions::publishInternalPorts() const {
  return values_.count("publish_internal_ports") && std::get<bool>(values_.at("publish_internal_ports"));
}

}  // namespace imagenets
