#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Histogram equalisation: global, or adaptive (CLAHE) when clip_limit > 0. A colour image is
// equalised on its luminance only (YCrCb), so hues do not shift.
class HistogramEqualization : public Block {
 public:
  HistogramEqualization() {
    addInput<sensor_msgs::Image>("image", "mono8 or bgr8/rgb8");
    addOutput<sensor_msgs::Image>("image", "equalised image, same encoding");
    addProperty<double>("clip_limit", 0.0, "0: global equalisation; > 0: CLAHE contrast limit").range(0, 100);
    addProperty<int>("tiles", 8, "CLAHE: tiles per image side").range(1, 64);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding, &header);
    const double clip = ctx.property<double>("clip_limit");
    const int tiles = ctx.property<int>("tiles");
    auto equalize = [&](const cv::Mat& gray, cv::Mat& out) {
      if (clip > 0) {
        cv::createCLAHE(clip, cv::Size(tiles, tiles))->apply(gray, out);
      } else {
        cv::equalizeHist(gray, out);
      }
    };
    OutputImage result = newOutputImage(cv::Size(in.cols, in.rows), in.type(), encoding, header);
    cv::Mat& out = result.mat;
    if (encoding == "mono8") {
      equalize(in, out);
    } else {
      const bool rgb = encoding == "rgb8";
      cv::Mat ycrcb;
      cv::cvtColor(in, ycrcb, rgb ? cv::COLOR_RGB2YCrCb : cv::COLOR_BGR2YCrCb);
      std::vector<cv::Mat> channels;
      cv::split(ycrcb, channels);
      equalize(channels[0], channels[0]);
      cv::merge(channels, ycrcb);
      cv::cvtColor(ycrcb, out, rgb ? cv::COLOR_YCrCb2RGB : cv::COLOR_YCrCb2BGR);
    }
    ctx.output("image", result.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::HistogramEqualization, "imagenets/HistogramEqualization", "preprocessing",
                         "Histogram equalisation (global or CLAHE)");
