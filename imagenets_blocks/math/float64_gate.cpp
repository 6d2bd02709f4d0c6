#include <cmath>
#include <limits>

#include <std_msgs/Float64.h>

#include "imagenets/registry.h"

namespace imagenets {
namespace blocks {

// Passes `value` on while `control` lies within [min, max], else NaN: a feedback score that is
// invalid when a second measure is out of bounds (e.g. a marker's confidence, rejected when its
// corners fit worse than a limit). A NaN control fails the bounds too.
class Float64Gate : public Block {
 public:
  Float64Gate() {
    addInput<std_msgs::Float64>("value", "the number to pass on");
    addInput<std_msgs::Float64>("control", "the number checked against [min, max]");
    addOutput<std_msgs::Float64>("value", "`value`, or NaN when `control` is outside [min, max]");
    addProperty<double>("min", -1e9, "lowest accepted control");
    addProperty<double>("max", 1e9, "highest accepted control");
  }

  void process(Context& ctx) override {
    const double control = ctx.input<std_msgs::Float64>("control")->data;
    const bool pass = control >= ctx.property<double>("min") && control <= ctx.property<double>("max");
    auto out = boost::make_shared<std_msgs::Float64>();
    out->data = pass ? ctx.input<std_msgs::Float64>("value")->data : std::numeric_limits<double>::quiet_NaN();
    ctx.output("value", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Float64Gate, "imagenets/Float64Gate", "math",
                         "A number, or NaN when a second number is out of bounds (invalidates a score)");
