#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Colour segmentation: pixels whose colour lies inside a box (in HSV or BGR) become white. In HSV
// a hue range with lower > upper wraps around red (e.g. 170..10).
class ColourRange : public Block {
 public:
  ColourRange() {
    addInput<sensor_msgs::Image>("image", "bgr8 or rgb8");
    addOutput<sensor_msgs::Image>("image", "binary mono8 image (0 / 255)");
    addProperty<std::string>("space", "hsv", "colour space of the bounds").choices({"hsv", "bgr"});
    addProperty<std::vector<double>>("lower", std::vector<double>{0, 100, 100},
                                     "lower bound per channel: HSV (hue 0..179, sat 0..255, val 0..255) or B, G, R");
    addProperty<std::vector<double>>("upper", std::vector<double>{10, 255, 255}, "upper bound per channel (inclusive)");
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"bgr8", "rgb8"}, &encoding, &header);
    const auto lower = bounds(ctx, "lower"), upper = bounds(ctx, "upper");
    const bool hsv = ctx.property<std::string>("space") == "hsv";
    cv::Mat converted;
    if (hsv) {
      cv::cvtColor(in, converted, encoding == "rgb8" ? cv::COLOR_RGB2HSV : cv::COLOR_BGR2HSV);
    } else if (encoding == "rgb8") {
      cv::cvtColor(in, converted, cv::COLOR_RGB2BGR);
    } else {
      converted = in;
    }
    OutputImage result = newOutputImage(cv::Size(in.cols, in.rows), CV_8UC1, "mono8", header);
    cv::Mat& out = result.mat;
    if (hsv && lower[0] > upper[0]) {  // hue wraps: [lower, 179] or [0, upper]
      cv::Mat a, b;
      cv::inRange(converted, cv::Scalar(lower[0], lower[1], lower[2]), cv::Scalar(179, upper[1], upper[2]), a);
      cv::inRange(converted, cv::Scalar(0, lower[1], lower[2]), cv::Scalar(upper[0], upper[1], upper[2]), b);
      cv::bitwise_or(a, b, out);
    } else {
      cv::inRange(converted, cv::Scalar(lower[0], lower[1], lower[2]), cv::Scalar(upper[0], upper[1], upper[2]), out);
    }
    ctx.output("image", result.msg);
  }

 private:
  static std::vector<double> bounds(const Context& ctx, const std::string& name) {
    auto v = ctx.property<std::vector<double>>(name);
    if (v.size() != 3) {
      throw BlockError("property '" + name + "': " + std::to_string(v.size()) + " values, expected 3 (one per channel)");
    }
    for (double x : v) {
      if (!(x >= 0 && x <= 255)) throw BlockError("property '" + name + "': value " + std::to_string(x) + " outside 0..255");
    }
    return v;
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ColourRange, "imagenets/ColourRange", "segmentation",
                         "Colour segmentation by an HSV or BGR range");
