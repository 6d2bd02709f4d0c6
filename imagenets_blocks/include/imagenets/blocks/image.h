// Image helpers shared by blocks: read an input image as a cv::Mat without copying, with a named
// error for a missing, empty or wrongly encoded image; publish a cv::Mat as a message.
#pragma once

#include <initializer_list>
#include <string>

#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>

#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

// The input image as a read-only cv::Mat sharing the message's pixels. Throws BlockError naming
// the port when the image is empty or its encoding is not one of `encodings` (empty = any).
cv::Mat inputImage(const Context& ctx, const std::string& port, std::initializer_list<const char*> encodings = {},
                   std::string* encoding = nullptr, std_msgs::Header* header = nullptr);

// Wraps `mat` (moved into the message, no second copy) as an image message.
sensor_msgs::ImagePtr toImageMsg(const cv::Mat& mat, const std::string& encoding, const std_msgs::Header& header);

// An output image message whose pixel buffer OpenCV writes into directly, so the result is not
// copied into the message afterwards:
//   OutputImage out(header, in.rows, in.cols, CV_8UC1, "mono8");
//   cv::threshold(in, out.mat(), ...);
//   ctx.output("image", out.finish());
// If an OpenCV call reallocates the matrix anyway, finish() copies it in (correct, just slower).
class OutputImage {
 public:
  OutputImage(const std_msgs::Header& header, int rows, int cols, int type, const std::string& encoding);
  cv::Mat& mat() { return mat_; }
  sensor_msgs::ImagePtr finish();

 private:
  sensor_msgs::ImagePtr msg_;
  cv::Mat mat_;
};

}  // namespace blocks
}  // namespace imagenets
