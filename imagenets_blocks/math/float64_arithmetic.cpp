#include <algorithm>
#include <cmath>

#include <std_msgs/Float64.h>

#include "imagenets/registry.h"

namespace imagenets {
namespace blocks {

// a (op) b on numbers, b from the input when linked, else the property `b`: e.g. a combined
// feedback score, confidence - 0.1 * reprojection error (two blocks). NaN in, NaN out.
class Float64Arithmetic : public Block {
 public:
  Float64Arithmetic() {
    addInput<std_msgs::Float64>("a", "left operand");
    addOptionalInput<std_msgs::Float64>("b", "right operand (else the property `b`)");
    addOutput<std_msgs::Float64>("result", "a (operation) b");
    addProperty<std::string>("operation", "add", "add, subtract, multiply, divide, min or max")
        .choices({"add", "subtract", "multiply", "divide", "min", "max"});
    addProperty<double>("b", 0.0, "right operand when input `b` is not linked");
  }

  void process(Context& ctx) override {
    const double a = ctx.input<std_msgs::Float64>("a")->data;
    const auto b_in = ctx.input<std_msgs::Float64>("b");
    const double b = b_in ? b_in->data : ctx.property<double>("b");
    const std::string op = ctx.property<std::string>("operation");
    auto out = boost::make_shared<std_msgs::Float64>();
    if (op == "add") out->data = a + b;
    else if (op == "subtract") out->data = a - b;
    else if (op == "multiply") out->data = a * b;
    else if (op == "divide") out->data = a / b;  // x / 0 is inf or NaN: an invalid score
    else if (std::isnan(a) || std::isnan(b)) out->data = std::nan("");
    else out->data = op == "min" ? std::min(a, b) : std::max(a, b);
    ctx.output("result", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Float64Arithmetic, "imagenets/Float64Arithmetic", "math",
                         "a + - * / min max b on numbers (e.g. to combine feedback scores)");
