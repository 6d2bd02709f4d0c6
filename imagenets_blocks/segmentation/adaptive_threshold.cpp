#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Adaptive threshold: each pixel is compared with the (mean or Gaussian-weighted) mean of its
// neighbourhood minus `offset`, so uneven lighting does not matter.
class AdaptiveThreshold : public Block {
 public:
  AdaptiveThreshold() {
    addInput<sensor_msgs::Image>("image", "mono8");
    addOutput<sensor_msgs::Image>("image", "binary mono8 image (0 / 255)");
    addProperty<int>("block_size", 21, "neighbourhood width in pixels (odd, >= 3)").range(3, 401);
    addProperty<double>("offset", 5.0, "a pixel is white if brighter than local mean - offset").range(-255, 255);
    addProperty<std::string>("method", "mean", "local mean: plain box or Gaussian-weighted").choices({"mean", "gaussian"});
    addProperty<bool>("invert", false, "dark pixels become white instead");
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8"}, nullptr, &header);
    const int block = ctx.property<int>("block_size");
    if (block % 2 == 0) throw BlockError("property 'block_size': " + std::to_string(block) + " is even (must be odd)");
    OutputImage out = newOutputImage(cv::Size(in.cols, in.rows), CV_8UC1, "mono8", header);
    cv::adaptiveThreshold(in, out.mat, 255,
                          ctx.property<std::string>("method") == "gaussian" ? cv::ADAPTIVE_THRESH_GAUSSIAN_C
                                                                            : cv::ADAPTIVE_THRESH_MEAN_C,
                          ctx.property<bool>("invert") ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY, block,
                          ctx.property<double>("offset"));
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::AdaptiveThreshold, "imagenets/AdaptiveThreshold", "segmentation",
                         "Threshold against the local mean (uneven lighting)");
