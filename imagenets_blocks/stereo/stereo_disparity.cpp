#include <limits>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Disparity of a rectified stereo pair by semi-global block matching (OpenCV SGBM, Hirschmueller
// 2008). Disparity d (pixels) = x_left - x_right of a scene point; invalid pixels are NaN.
class StereoDisparity : public Block {
 public:
  StereoDisparity() {
    addInput<sensor_msgs::Image>("left", "rectified left image (mono8 or bgr8/rgb8)");
    addInput<sensor_msgs::Image>("right", "rectified right image, same size and encoding");
    addOutput<sensor_msgs::Image>("disparity", "32FC1 disparity in pixels on the left image, NaN where unknown");
    addProperty<int>("min_disparity", 0, "smallest disparity searched (pixels)").range(-1024, 1024);
    addProperty<int>("num_disparities", 128, "size of the search range (pixels, multiple of 16)").range(16, 1024);
    addProperty<int>("block_size", 5, "matched block width (odd pixels)").range(1, 31);
    addProperty<int>("uniqueness_ratio", 10, "margin (%) by which the best match must win").range(0, 100);
    addProperty<int>("speckle_window_size", 100, "largest speckle region to remove (pixels); 0: off").range(0, 10000);
    addProperty<int>("speckle_range", 2, "disparity variation inside a connected region (pixels)").range(0, 64);
    addProperty<int>("disp12_max_diff", 1, "left-right consistency tolerance (pixels); -1: off").range(-1, 1024);
    addProperty<int>("pre_filter_cap", 63, "clip of the prefiltered x-derivative").range(1, 63);
    addProperty<std::string>("mode", "sgbm", "sgbm: 5 directions; hh: full 8 directions; sgbm_3way: faster")
        .choices({"sgbm", "hh", "sgbm_3way"});
  }

  void process(Context& ctx) override {
    std::string le, re;
    std_msgs::Header header;
    const cv::Mat left = inputImage(ctx, "left", {"mono8", "bgr8", "rgb8"}, &le, &header);
    const cv::Mat right = inputImage(ctx, "right", {"mono8", "bgr8", "rgb8"}, &re);
    if (left.size() != right.size()) {
      throw BlockError("inputs 'left' (" + std::to_string(left.cols) + "x" + std::to_string(left.rows) + ") and 'right' (" +
                       std::to_string(right.cols) + "x" + std::to_string(right.rows) + ") differ in size");
    }
    if (le != re) throw BlockError("inputs 'left' (" + le + ") and 'right' (" + re + ") differ in encoding");
    const int num = ctx.property<int>("num_disparities"), block = ctx.property<int>("block_size");
    if (num % 16 != 0) throw BlockError("property 'num_disparities': " + std::to_string(num) + " is not a multiple of 16");
    if (block % 2 == 0) throw BlockError("property 'block_size': " + std::to_string(block) + " is even (must be odd)");
    const int min_d = ctx.property<int>("min_disparity");
    if (num >= left.cols) {
      throw BlockError("property 'num_disparities': " + std::to_string(num) + " is not below the image width " +
                       std::to_string(left.cols));
    }
    const int channels = left.channels();
    const std::string mode = ctx.property<std::string>("mode");
    auto sgbm = cv::StereoSGBM::create(min_d, num, block, 8 * channels * block * block, 32 * channels * block * block,
                                       ctx.property<int>("disp12_max_diff"), ctx.property<int>("pre_filter_cap"),
                                       ctx.property<int>("uniqueness_ratio"), ctx.property<int>("speckle_window_size"),
                                       ctx.property<int>("speckle_range"),
                                       mode == "hh" ? cv::StereoSGBM::MODE_HH
                                                    : mode == "sgbm_3way" ? cv::StereoSGBM::MODE_SGBM_3WAY
                                                                          : cv::StereoSGBM::MODE_SGBM);
    cv::Mat fixed;  // 16 x disparity, CV_16S; below min_disparity = invalid
    sgbm->compute(left, right, fixed);
    OutputImage disparity = newOutputImage(cv::Size(fixed.cols, fixed.rows), CV_32FC1, "32FC1", header);
    fixed.convertTo(disparity.mat, CV_32F, 1.0 / 16);
    disparity.mat.setTo(std::numeric_limits<float>::quiet_NaN(), fixed < min_d * 16);
    ctx.output("disparity", disparity.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::StereoDisparity, "imagenets/StereoDisparity", "stereo",
                         "Disparity of a rectified stereo pair (OpenCV SGBM)");
