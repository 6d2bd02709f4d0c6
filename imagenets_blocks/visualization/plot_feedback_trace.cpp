#include "imagenets/blocks/image.h"
#include "imagenets/vision/plot.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Plots a feedback sweep (paper Fig. 3.3): score over the tuned property, chosen value marked.
class PlotFeedbackTrace : public Block {
 public:
  PlotFeedbackTrace() {
    addInput<imagenets::FeedbackTrace>("trace", "the `feedback_trace` output of a block with feedback");
    addOutput<sensor_msgs::Image>("image", "bgr8 plot");
    addProperty<int>("width", 640, "image width (pixels)").range(160, 4096);
    addProperty<int>("height", 400, "image height (pixels)").range(120, 4096);
  }

  void process(Context& ctx) override {
    auto trace = ctx.input<imagenets::FeedbackTrace>("trace");
    if (!trace) throw BlockError("input 'trace': no trace");
    cv::Mat img;
    try {
      img = plot::plotFeedbackTrace(*trace, ctx.property<int>("width"), ctx.property<int>("height"));
    } catch (const std::invalid_argument& e) {
      throw BlockError(std::string("input 'trace': ") + e.what());
    }
    std_msgs::Header header;
    header.frame_id = "plot";
    ctx.output("image", toImageMsg(img, "bgr8", header));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::PlotFeedbackTrace, "imagenets/PlotFeedbackTrace", "visualization",
                         "Plots a feedback sweep (score over property value)");
