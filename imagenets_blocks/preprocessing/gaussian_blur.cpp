#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Smooths an image with a Gaussian kernel (noise suppression before segmentation).
class GaussianBlur : public Block {
 public:
  GaussianBlur() {
    addInput<sensor_msgs::Image>("image", "any 8-bit image");
    addOutput<sensor_msgs::Image>("image", "the blurred image, same encoding");
    addProperty<int>("kernel_size", 5, "kernel width and height in pixels (odd)").range(1, 31);
    addProperty<double>("sigma", 0.0, "standard deviation in pixels; 0 derives it from kernel_size").range(0, 20);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding, &header);
    const int k = ctx.property<int>("kernel_size");
    if (k % 2 == 0) throw BlockError("property 'kernel_size': " + std::to_string(k) + " is even (must be odd)");
    OutputImage out = newOutputImage(in.size(), in.type(), encoding, header);
    cv::GaussianBlur(in, out.mat, cv::Size(k, k), ctx.property<double>("sigma"));
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::GaussianBlur, "imagenets/GaussianBlur", "preprocessing",
                         "Gaussian smoothing");
