#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// A disparity (or depth) image as a colour picture: values from `min` to `max` along a colour
// map (near = warm with JET/TURBO for disparity), unknown (NaN) pixels black.
class ColouriseDisparity : public Block {
 public:
  ColouriseDisparity() {
    addInput<sensor_msgs::Image>("disparity", "32FC1 (pixels or metres); NaN = unknown");
    addOutput<sensor_msgs::Image>("image", "bgr8 picture");
    addProperty<double>("min", 0.0, "value shown at the cold end; min = max = 0: the finite range of the image")
        .range(-1e6, 1e6);
    addProperty<double>("max", 0.0, "value shown at the warm end").range(-1e6, 1e6);
    addProperty<std::string>("colour_map", "turbo", "OpenCV colour map").choices({"turbo", "jet", "viridis", "gray"});
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat d = inputImage(ctx, "disparity", {"32FC1"}, nullptr, &header);
    const cv::Mat finite = d == d;  // NaN != NaN
    double lo = ctx.property<double>("min"), hi = ctx.property<double>("max");
    if (lo == 0 && hi == 0) {
      cv::Mat also_finite = finite & (cv::abs(d) < std::numeric_limits<float>::infinity());
      if (cv::countNonZero(also_finite) == 0) throw BlockError("input 'disparity': no finite value");
      cv::minMaxLoc(d, &lo, &hi, nullptr, nullptr, also_finite);
    }
    if (!(hi > lo)) hi = lo + 1;
    cv::Mat scaled;
    d.convertTo(scaled, CV_8U, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
    cv::Mat out;
    const std::string map = ctx.property<std::string>("colour_map");
    if (map == "gray") {
      cv::cvtColor(scaled, out, cv::COLOR_GRAY2BGR);
    } else {
      cv::applyColorMap(scaled, out, map == "jet" ? cv::COLORMAP_JET : map == "viridis" ? cv::COLORMAP_VIRIDIS : cv::COLORMAP_TURBO);
    }
    out.setTo(cv::Scalar(0, 0, 0), ~finite);
    ctx.output("image", toImageMsg(out, "bgr8", header));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ColouriseDisparity, "imagenets/ColouriseDisparity", "visualization",
                         "Disparity / depth image as a colour picture");
