#include <opencv2/imgproc.hpp>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Otsu's threshold: the gray level that best separates the histogram into two classes (maximal
// between-class variance), chosen per image.
class OtsuThreshold : public Block {
 public:
  OtsuThreshold() {
    addInput<sensor_msgs::Image>("image", "mono8");
    addOutput<sensor_msgs::Image>("image", "binary mono8 image (0 / 255)");
    addOutput<std_msgs::Float64>("threshold", "the gray level Otsu chose");
    addProperty<bool>("invert", false, "dark pixels become white instead");
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8"}, nullptr, &header);
    OutputImage out = newOutputImage(cv::Size(in.cols, in.rows), CV_8UC1, "mono8", header);
    const int type = (ctx.property<bool>("invert") ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY) | cv::THRESH_OTSU;
    boost::shared_ptr<std_msgs::Float64> level(new std_msgs::Float64);
    level->data = cv::threshold(in, out.mat, 0, 255, type);
    ctx.output("image", out.msg);
    ctx.output("threshold", level);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::OtsuThreshold, "imagenets/OtsuThreshold", "segmentation",
                         "Automatic threshold by Otsu's method");
