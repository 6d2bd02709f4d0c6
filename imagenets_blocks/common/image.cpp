#include "imagenets/blocks/image.h"

#include <algorithm>

#include <cv_bridge/cv_bridge.h>

namespace imagenets {
namespace blocks {

cv::Mat inputImage(const Context& ctx, const std::string& port, std::initializer_list<const char*> encodings,
                   std::string* encoding, std_msgs::Header* header) {
  auto msg = ctx.input<sensor_msgs::Image>(port);
  if (!msg) throw BlockError("input '" + port + "': no image");
  if (msg->width == 0 || msg->height == 0 || msg->data.empty()) {
    throw BlockError("input '" + port + "': empty image (" + std::to_string(msg->width) + "x" +
                     std::to_string(msg->height) + ")");
  }
  if (encodings.size() > 0 &&
      std::none_of(encodings.begin(), encodings.end(), [&](const char* e) { return msg->encoding == e; })) {
    std::string list;  // built only for the error: every block reads its images through here
    for (const char* e : encodings) list += (list.empty() ? "" : ", ") + std::string(e);
    throw BlockError("input '" + port + "': encoding '" + msg->encoding + "' not accepted (expected " + list + ")");
  }
  if (encoding) *encoding = msg->encoding;
  if (header) *header = msg->header;
  try {
    return cv_bridge::toCvShare(msg)->image;
  } catch (const cv_bridge::Exception& e) {
    throw BlockError("input '" + port + "': " + e.what());
  }
}

OutputImage newOutputImage(cv::Size size, int cv_type, const std::string& encoding, const std_msgs::Header& header) {
  OutputImage out;
  out.msg = boost::make_shared<sensor_msgs::Image>();
  out.msg->header = header;
  out.msg->encoding = encoding;
  out.msg->height = size.height;
  out.msg->width = size.width;
  out.msg->step = static_cast<uint32_t>(size.width * CV_ELEM_SIZE(cv_type));
  out.msg->data.resize(static_cast<size_t>(out.msg->step) * size.height);
  out.mat = cv::Mat(size, cv_type, out.msg->data.data(), out.msg->step);
  return out;
}

sensor_msgs::ImagePtr toImageMsg(const cv::Mat& mat, const std::string& encoding, const std_msgs::Header& header) {
  return cv_bridge::CvImage(header, encoding, mat).toImageMsg();
}

}  // namespace blocks
}  // namespace imagenets
