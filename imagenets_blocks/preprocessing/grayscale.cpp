#include <map>

#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Converts a colour image to 8-bit gray; a gray image passes through unchanged (same pointer).
class Grayscale : public Block {
 public:
  Grayscale() {
    addInput<sensor_msgs::Image>("image", "bgr8, rgb8, bgra8, rgba8 or mono8");
    addOutput<sensor_msgs::Image>("image", "mono8");
  }

  void process(Context& ctx) override {
    std::string encoding;
    cv::Mat in = inputImage(ctx, "image", {"bgr8", "rgb8", "bgra8", "rgba8", "mono8"}, &encoding);
    if (encoding == "mono8") {
      ctx.setOutput("image", ctx.inputValue("image"));
      return;
    }
    const std_msgs::Header header = ctx.input<sensor_msgs::Image>("image")->header;
    static const std::map<std::string, int> codes{{"bgr8", cv::COLOR_BGR2GRAY},
                                                  {"rgb8", cv::COLOR_RGB2GRAY},
                                                  {"bgra8", cv::COLOR_BGRA2GRAY},
                                                  {"rgba8", cv::COLOR_RGBA2GRAY}};
    OutputImage gray = newOutputImage(in.size(), CV_8UC1, "mono8", header);
    cv::cvtColor(in, gray.mat, codes.at(encoding));
    ctx.output("image", gray.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Grayscale, "imagenets/Grayscale", "preprocessing",
                         "Colour to 8-bit gray");
