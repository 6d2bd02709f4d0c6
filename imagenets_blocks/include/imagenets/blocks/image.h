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

// An output image message and a cv::Mat viewing its pixel buffer: OpenCV functions given `mat`
// as destination write straight into the message, so no copy is made afterwards.
struct OutputImage {
  sensor_msgs::ImagePtr msg;
  cv::Mat mat;
};
OutputImage newOutputImage(cv::Size size, int cv_type, const std::string& encoding, const std_msgs::Header& header);

// Copies `mat` into a new image message (use newOutputImage where the size is known up front).
sensor_msgs::ImagePtr toImageMsg(const cv::Mat& mat, const std::string& encoding, const std_msgs::Header& header);

}  // namespace blocks
}  // namespace imagenets
