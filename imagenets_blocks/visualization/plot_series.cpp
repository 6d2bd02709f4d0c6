#include <std_msgs/Float64MultiArray.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/plot.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Plots a series of numbers (y over x, or over the sample index) into an image.
class PlotSeries : public Block {
 public:
  PlotSeries() {
    addInput<std_msgs::Float64MultiArray>("y", "values; NaN = missing");
    addOptionalInput<std_msgs::Float64MultiArray>("x", "abscissae, same length as y; absent: 0, 1, 2, ...");
    addOutput<sensor_msgs::Image>("image", "bgr8 plot");
    addProperty<std::string>("title", "", "title above the plot");
    addProperty<std::string>("x_label", "index", "label of the x axis");
    addProperty<std::string>("y_label", "value", "label of the y axis");
    addProperty<int>("width", 640, "image width (pixels)").range(160, 4096);
    addProperty<int>("height", 400, "image height (pixels)").range(120, 4096);
  }

  void process(Context& ctx) override {
    auto y = ctx.input<std_msgs::Float64MultiArray>("y");
    if (!y) throw BlockError("input 'y': no values");
    if (y->data.empty()) throw BlockError("input 'y': empty array");
    plot::Series s;
    s.y = y->data;
    if (auto x = ctx.input<std_msgs::Float64MultiArray>("x")) {
      if (x->data.size() != y->data.size()) {
        throw BlockError("inputs 'x' (" + std::to_string(x->data.size()) + " values) and 'y' (" +
                         std::to_string(y->data.size()) + " values) differ in length");
      }
      s.x = x->data;
    } else {
      for (size_t i = 0; i < s.y.size(); ++i) s.x.push_back(static_cast<double>(i));
    }
    s.points = s.y.size() <= 200;
    plot::Options o;
    o.title = ctx.property<std::string>("title");
    o.x_label = ctx.property<std::string>("x_label");
    o.y_label = ctx.property<std::string>("y_label");
    o.width = ctx.property<int>("width");
    o.height = ctx.property<int>("height");
    std_msgs::Header header;
    header.frame_id = "plot";
    ctx.output("image", toImageMsg(plot::plotSeries({s}, o), "bgr8", header));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PlotSeries, "imagenets/PlotSeries", "visualization",
                         "Plots a series of numbers into an image");
