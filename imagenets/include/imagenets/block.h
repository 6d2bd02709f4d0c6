// The Block API. A block declares its typed ports and properties in its constructor and does its
// work in process(). It knows nothing of nets, threads or ROS topics: the executor and the
// nodelet host feed it through a Context.
//
//   class Threshold : public imagenets::Block {
//    public:
//     Threshold() {
//       addInput<sensor_msgs::Image>("image", "8-bit gray image");
//       addOutput<sensor_msgs::Image>("image", "binary image (0/255)");
//       addProperty<int>("threshold", 128, "gray level above which a pixel is white").range(0, 255);
//     }
//     void process(imagenets::Context& ctx) override { ... }
//   };
//   IMAGENETS_REGISTER_BLOCK(Threshold, "imagenets/Threshold", "segmentation", "Fixed threshold");
//
// Every host runs a block the same way: invokeBlock() (block_invocation.h).
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "imagenets/port_type.h"
#include "imagenets/property.h"
#include "imagenets/run_events.h"

namespace imagenets {

struct PortSpec {
  std::string name;
  const PortType* type = nullptr;
  std::string doc;
  bool optional = false;  // an optional input may stay empty; the block still runs
};
// "name [type], ..." (or "none"), for messages.
std::string portList(const std::vector<PortSpec>& ports);

// What a block sees during one process() call: its inputs, a snapshot of its properties, and
// where its outputs go. Several contexts of one block may be alive at once (feedback trials run in
// parallel), so a block keeps per-run data here, not in members.
class Context {
 public:
  // `block_name`, the port lists and the input values must outlive the context (the block's own,
  // and its host's). `input_values` per input port; a shorter list leaves the last ones empty.
  Context(const std::string& block_name, const std::vector<PortSpec>& inputs,
          const std::vector<PortSpec>& outputs, const std::vector<Value>& input_values,
          std::shared_ptr<const PropertyValues> properties);

  const std::string& blockName() const { return block_name_; }

  template <class M>
  boost::shared_ptr<const M> input(const std::string& port) const {
    return inputValue(port).as<M>();
  }
  bool hasInput(const std::string& port) const { return static_cast<bool>(inputValue(port)); }
  const Value& inputValue(const std::string& port) const;

  template <class M>
  void output(const std::string& port, const boost::shared_ptr<const M>& msg) {
    setOutput(port, PortType::of<M>().wrap(msg));
  }
  template <class M>
  void output(const std::string& port, const boost::shared_ptr<M>& msg) {
    output(port, boost::shared_ptr<const M>(msg));
  }
  void setOutput(const std::string& port, const Value& value);

  template <class T>
  T property(const std::string& name) const {
    const PropertyValue& v = propertyValue(name);
    if (const T* typed = std::get_if<T>(&v)) return *typed;
    throw std::logic_error("block '" + block_name_ + "': property '" + name +
                           "' read with the wrong C++ type");
  }
  const PropertyValue& propertyValue(const std::string& name) const;
  const PropertyValues& properties() const { return *properties_; }

  // For a block that runs something inside (a sub-net): emit() passes that run's events to whoever
  // watches this run, with this block's name prefixed to the event's block path ("outer/inner");
  // cancelled() says the run was cancelled, and the block then stops early by throwing RunCancelled.
  void emit(RunEvent event) const;
  bool cancelled() const { return channel_.cancelled && channel_.cancelled(); }
  void setRunChannel(RunChannel channel) { channel_ = std::move(channel); }
  // The channel to hand to what runs inside (Executor::nestIn): its events reach this run's
  // watchers under this block's path, and this run's cancel reaches it.
  RunChannel innerChannel() const;

  std::vector<Value>& outputs() { return output_values_; }

 private:
  const std::string& block_name_;
  const std::vector<PortSpec>& inputs_;
  const std::vector<PortSpec>& outputs_;
  const std::vector<Value>& input_values_;
  std::vector<Value> output_values_;
  std::shared_ptr<const PropertyValues> properties_;
  RunChannel channel_;
};

// An error a block reports about its input or configuration; the executor prefixes the block.
struct BlockError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Thrown by a block that stopped early because ctx.cancelled(): the block is NotRun ("cancelled")
// and stays out of date, not failed.
struct RunCancelled : std::runtime_error {
  RunCancelled() : std::runtime_error("cancelled") {}
};

struct BlockInfo;
class Net;

class Block {
 public:
  virtual ~Block() = default;

  // Called once after the load-time property values are set. A block whose ports depend on a
  // property (a sub-net, a port of configurable type) declares them here.
  virtual void configure() {}
  // Does the work. May run concurrently for feedback trials: keep per-run data in ctx.
  virtual void process(Context& ctx) = 0;
  // A block that runs a whole net inside (a sub-net) shows it here, for drawing and inspection.
  virtual const Net* subNet() const { return nullptr; }

  const std::vector<PortSpec>& inputs() const { return inputs_; }
  const std::vector<PortSpec>& outputs() const { return outputs_; }
  const std::vector<PropertySpec>& propertySpecs() const { return property_specs_; }
  // An output the engine adds to a block for a feature of the net it sits in (the feedback trace):
  // called before configure(); the engine, not the block, sets it.
  PortSpec& attachOutput(const std::string& name, const PortType& type, const std::string& doc) {
    return addOutput(name, type, doc);
  }
  const PortSpec* findInput(const std::string& name) const;
  const PortSpec* findOutput(const std::string& name) const;
  const PropertySpec* findProperty(const std::string& name) const;
  // The declaration of `name`; throws PropertyError "unknown property 'x' (known: a, b)".
  const PropertySpec& propertySpec(const std::string& name) const;
  // A written value for `name` (PropertySpec::parse); throws PropertyError "unknown property 'x'
  // (known: a, b)" or "property 'x': <why>".
  PropertyValue parseProperty(const std::string& name, const std::string& text, const std::string& base_dir = "") const;
  int inputIndex(const std::string& name) const;   // -1 if none
  int outputIndex(const std::string& name) const;  // -1 if none

  // Current property values (thread-safe). setProperty validates and throws PropertyError.
  PropertyValues propertyValues() const;
  // The same, shared and never changed afterwards: a setProperty makes a new one (copy on write),
  // so a run reads its block's properties without copying them.
  std::shared_ptr<const PropertyValues> propertySnapshot() const;
  PropertyValue propertyValue(const std::string& name) const;
  void setProperty(const std::string& name, const PropertyValue& value);

  // Set by the registry when the block is created.
  const BlockInfo* info() const { return info_; }
  void setInfo(const BlockInfo* info) { info_ = info; }

 protected:
  template <class M>
  PortSpec& addInput(const std::string& name, const std::string& doc) {
    return addInput(name, PortType::of<M>(), doc);
  }
  template <class M>
  PortSpec& addOptionalInput(const std::string& name, const std::string& doc) {
    PortSpec& p = addInput(name, PortType::of<M>(), doc);
    p.optional = true;
    return p;
  }
  template <class M>
  PortSpec& addOutput(const std::string& name, const std::string& doc) {
    return addOutput(name, PortType::of<M>(), doc);
  }
  PortSpec& addInput(const std::string& name, const PortType& type, const std::string& doc);
  PortSpec& addOutput(const std::string& name, const PortType& type, const std::string& doc);

  template <class T>
  PropertySpec& addProperty(const std::string& name, const T& default_value, const std::string& doc) {
    return addPropertySpec(PropertySpec(name, PropertyTraits<T>::kind, default_value, doc));
  }
  PropertySpec& addProperty(const std::string& name, const char* default_value, const std::string& doc) {
    return addProperty<std::string>(name, default_value, doc);
  }
  PropertySpec& addPropertySpec(PropertySpec spec);

  // For configure(): the current value of a property.
  template <class T>
  T property(const std::string& name) const {
    return std::get<T>(propertyValue(name));
  }

 private:
  std::vector<PortSpec> inputs_, outputs_;
  std::vector<PropertySpec> property_specs_;
  mutable std::mutex values_mutex_;
  std::shared_ptr<const PropertyValues> values_ = std::make_shared<const PropertyValues>();
  const BlockInfo* info_ = nullptr;
};

// Same ports (names, types, optional) in the same order: the links of a net, or the topics of a
// nodelet, made for one still fit the other.
bool samePorts(const Block& a, const Block& b);
// Reconfiguring a block whose properties change: `fresh`, a new instance of `current`'s type, takes
// `current`'s property values with `changes` over them and is configured, so what configure() reads
// (a sub-net's net, a marker file, ports) takes effect too. Throws PropertyError naming the
// property, or what configure() throws; `current` is left as it was.
void configureLike(Block& fresh, const Block& current, const PropertyValues& changes);

}  // namespace imagenets
