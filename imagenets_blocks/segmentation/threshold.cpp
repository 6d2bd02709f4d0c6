#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Fixed-threshold segmentation: pixels brighter than `threshold` become 255, the others 0.
class Threshold : public Block {
 public:
  Threshold() {
    addInput<sensor_msgs::Image>("image", "mono8");
    addOutput<sensor_msgs::Image>("image", "binary mono8 image (0 / 255)");
    addProperty<int>("threshold", 128, "gray level; brighter pixels become white").range(0, 255);
    addProperty<bool>("invert", false, "dark pixels become white instead");
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    cv::Mat in = inputImage(ctx, "image", {"mono8"}, nullptr, &header);
    OutputImage out = newOutputImage(in.size(), CV_8UC1, "mono8", header);
    const int type = ctx.property<bool>("invert") ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY;
    cv::threshold(in, out.mat, ctx.property<int>("threshold"), 255, type);
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Threshold, "imagenets/Threshold", "segmentation",
                         "Fixed threshold");
