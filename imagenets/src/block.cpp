#include "imagenets/block.h"

#include "imagenets/registry.h"

namespace imagenets {

Context::Context(const std::string& block_name, const std::vector<PortSpec>& inputs,
                 const std::vector<PortSpec>& outputs, const std::vector<Value>& input_values,
                 std::shared_ptr<const PropertyValues> properties)
    : block_name_(block_name),
      inputs_(inputs),
      outputs_(outputs),
      input_values_(input_values),
      output_values_(outputs.size()),
      properties_(std::move(properties)) {}

const Value& Context::inputValue(const std::string& port) const {
  static const Value none;
  for (size_t i = 0; i < inputs_.size(); ++i) {
    if (inputs_[i].name == port) return i < input_values_.size() ? input_values_[i] : none;
  }
  throw std::logic_error("block '" + block_name_ + "' has no input port '" + port + "'");
}

void Context::setOutput(const std::string& port, const Value& value) {
  for (size_t i = 0; i < outputs_.size(); ++i) {
    if (outputs_[i].name != port) continue;
    if (value && value.type != outputs_[i].type && value.type->name != outputs_[i].type->name) {
      throw std::logic_error("block '" + block_name_ + "': output '" + port + "' is " +
                             outputs_[i].type->name + ", not " + value.type->name);
    }
    output_values_[i] = value;
    return;
  }
  throw std::logic_error("block '" + block_name_ + "' has no output port '" + port + "'");
}

void Context::emit(RunEvent event) const {
  if (!channel_.emit) return;
  event.block = event.block.empty() ? block_name_ : block_name_ + "/" + event.block;
  channel_.emit(event);
}

RunChannel Context::innerChannel() const {
  return RunChannel{[this](const RunEvent& e) { emit(e); }, [this] { return cancelled(); }};
}

const PropertyValue& Context::propertyValue(const std::string& name) const {
  auto it = properties_->find(name);
  if (it == properties_->end()) {
    throw std::logic_error("block '" + block_name_ + "' has no property '" + name + "'");
  }
  return it->second;
}

std::string portList(const std::vector<PortSpec>& ports) {
  if (ports.empty()) return "none";
  std::string out;
  for (const auto& p : ports) out += (out.empty() ? "" : ", ") + p.name + " [" + p.type->name + "]";
  return out;
}

namespace {
template <class T>
const T* findByName(const std::vector<T>& items, const std::string& name) {
  for (const auto& item : items) {
    if (item.name() == name) return &item;
  }
  return nullptr;
}
int indexOf(const std::vector<PortSpec>& ports, const std::string& name) {
  for (size_t i = 0; i < ports.size(); ++i) {
    if (ports[i].name == name) return static_cast<int>(i);
  }
  return -1;
}
}  // namespace

const PortSpec* Block::findInput(const std::string& name) const {
  int i = indexOf(inputs_, name);
  return i < 0 ? nullptr : &inputs_[i];
}
const PortSpec* Block::findOutput(const std::string& name) const {
  int i = indexOf(outputs_, name);
  return i < 0 ? nullptr : &outputs_[i];
}
int Block::inputIndex(const std::string& name) const { return indexOf(inputs_, name); }
int Block::outputIndex(const std::string& name) const { return indexOf(outputs_, name); }

const PropertySpec* Block::findProperty(const std::string& name) const {
  return findByName(property_specs_, name);
}

PortSpec& Block::addInput(const std::string& name, const PortType& type, const std::string& doc) {
  if (findInput(name)) throw std::logic_error("input port '" + name + "' declared twice");
  inputs_.push_back(PortSpec{name, &type, doc, false});
  return inputs_.back();
}

PortSpec& Block::addOutput(const std::string& name, const PortType& type, const std::string& doc) {
  if (findOutput(name)) throw std::logic_error("output port '" + name + "' declared twice");
  outputs_.push_back(PortSpec{name, &type, doc, false});
  return outputs_.back();
}

PropertySpec& Block::addPropertySpec(PropertySpec spec) {
  if (findProperty(spec.name())) throw std::logic_error("property '" + spec.name() + "' declared twice");
  {
    std::lock_guard<std::mutex> lock(values_mutex_);
    auto values = std::make_shared<PropertyValues>(*values_);
    (*values)[spec.name()] = spec.defaultValue();
    values_ = std::move(values);
  }
  property_specs_.push_back(std::move(spec));
  return property_specs_.back();
}

PropertyValues Block::propertyValues() const { return *propertySnapshot(); }

std::shared_ptr<const PropertyValues> Block::propertySnapshot() const {
  std::lock_guard<std::mutex> lock(values_mutex_);
  return values_;
}

PropertyValue Block::propertyValue(const std::string& name) const {
  const auto values = propertySnapshot();
  auto it = values->find(name);
  if (it == values->end()) throw std::logic_error("no property '" + name + "'");
  return it->second;
}

const PropertySpec& Block::propertySpec(const std::string& name) const {
  std::vector<const PropertySpec*> specs;
  for (const PropertySpec& s : property_specs_) specs.push_back(&s);
  return findPropertySpec(specs, name);
}

PropertyValue Block::parseProperty(const std::string& name, const std::string& text, const std::string& base_dir) const {
  std::vector<const PropertySpec*> specs;
  for (const PropertySpec& s : property_specs_) specs.push_back(&s);
  return parseNamedProperty(specs, name, text, base_dir);
}

void Block::setProperty(const std::string& name, const PropertyValue& value) {
  PropertyValue checked = propertySpec(name).validate(value);
  std::lock_guard<std::mutex> lock(values_mutex_);
  auto values = std::make_shared<PropertyValues>(*values_);
  (*values)[name] = std::move(checked);
  values_ = std::move(values);
}

bool samePorts(const Block& a, const Block& b) {
  auto same = [](const std::vector<PortSpec>& x, const std::vector<PortSpec>& y) {
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i) {
      if (x[i].name != y[i].name || x[i].type != y[i].type || x[i].optional != y[i].optional) return false;
    }
    return true;
  };
  return same(a.inputs(), b.inputs()) && same(a.outputs(), b.outputs());
}

void configureLike(Block& fresh, const Block& current, const PropertyValues& changes) {
  if (!fresh.info()) fresh.setInfo(current.info());
  for (const auto& [name, value] : current.propertyValues()) {
    const auto changed = changes.find(name);
    fresh.setProperty(name, changed != changes.end() ? changed->second : value);
  }
  for (const auto& [name, value] : changes) {
    // One the current block does not know (all of its own are set above).
    if (!current.findProperty(name)) fresh.setProperty(name, value);
  }
  fresh.configure();
}

}  // namespace imagenets
