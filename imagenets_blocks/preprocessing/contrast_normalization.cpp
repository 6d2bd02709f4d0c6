#include <opencv2/core.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Linear contrast stretch: the darkest pixel becomes `low`, the brightest `high` (all channels
// together, so colours keep their balance). A flat image passes through unchanged.
class ContrastNormalization : public Block {
 public:
  ContrastNormalization() {
    addInput<sensor_msgs::Image>("image", "mono8 or bgr8/rgb8");
    addOutput<sensor_msgs::Image>("image", "stretched image, same encoding");
    addProperty<int>("low", 0, "output level of the darkest pixel").range(0, 255);
    addProperty<int>("high", 255, "output level of the brightest pixel").range(0, 255);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding, &header);
    const int low = ctx.property<int>("low"), high = ctx.property<int>("high");
    if (low >= high) {
      throw BlockError("properties 'low' (" + std::to_string(low) + ") and 'high' (" + std::to_string(high) +
                       "): low must be below high");
    }
    double lo = 0, hi = 0;
    cv::minMaxLoc(in.reshape(1), &lo, &hi);
    if (hi <= lo) {
      ctx.setOutput("image", ctx.inputValue("image"));
      return;
    }
    const double gain = (high - low) / (hi - lo);
    OutputImage out = newOutputImage(cv::Size(in.cols, in.rows), in.type(), encoding, header);
    in.convertTo(out.mat, CV_8U, gain, low - lo * gain);
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ContrastNormalization, "imagenets/ContrastNormalization", "preprocessing",
                         "Linear contrast stretch to a gray-level range");
