// An input of a sub-net (paper 3.5): becomes an input port of the outer `imagenets/Executor`
// block, which feeds it. Passes its value on unchanged (same pointer).
#include "imagenets/registry.h"

namespace imagenets {

class ExecutorInput : public Block {
 public:
  ExecutorInput() {
    addProperty<std::string>("port", "", "name of the port on the outer Executor block (default: this block's name)");
    addProperty<std::string>("type", "sensor_msgs/Image", "message type of the port, e.g. std_msgs/Float64");
  }

  void configure() override {
    const PortType& type = portType(property<std::string>("type"));
    addInput("value", type, "set by the outer net");
    addOutput("value", type, "the value, unchanged");
  }

  void process(Context& ctx) override { ctx.setOutput("value", ctx.inputValue("value")); }

  static const PortType& portType(const std::string& name) {
    const PortType* type = PortType::find(name);
    if (!type) {
      std::string known;
      for (const auto& n : PortType::names()) known += (known.empty() ? "" : ", ") + n;
      throw PropertyError("property 'type': unknown message type '" + name + "' (known: " + known + ")");
    }
    return *type;
  }
};

// An output of a sub-net: becomes an output port of the outer `imagenets/Executor` block.
class ExecutorOutput : public Block {
 public:
  ExecutorOutput() {
    addProperty<std::string>("port", "", "name of the port on the outer Executor block (default: this block's name)");
    addProperty<std::string>("type", "sensor_msgs/Image", "message type of the port, e.g. std_msgs/Float64");
  }

  void configure() override {
    const PortType& type = ExecutorInput::portType(property<std::string>("type"));
    addInput("value", type, "what the sub-net hands out");
    addOutput("value", type, "the value, read by the outer Executor block");
  }

  void process(Context& ctx) override { ctx.setOutput("value", ctx.inputValue("value")); }
};

}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::ExecutorInput, "imagenets/ExecutorInput", "executor",
                         "Input port of a sub-net");
IMAGENETS_REGISTER_BLOCK(imagenets::ExecutorOutput, "imagenets/ExecutorOutput", "executor",
                         "Output port of a sub-net");
