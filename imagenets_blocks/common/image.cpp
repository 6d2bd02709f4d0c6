#include "imagenets/blocks/image.h"

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
  if (encodings.size() > 0) {
    bool accepted = false;
    std::string list;
    for (const char* e : encodings) {
      accepted = accepted || msg->encoding == e;
      list += (list.empty() ? "" : ", ") + std::string(e);
    }
    if (!accepted) {
      throw BlockError("input '" + port + "': encoding '" + msg->encoding + "' not accepted (expected " + list + ")");
    }
  }
  if (encoding) *encoding = msg->encoding;
  if (header) *header = msg->header;
  try {
    return cv_bridge::toCvShare(msg)->image;
  } catch (const cv_bridge::Exception& e) {
    throw BlockError("input '" + port + "': " + e.what());
  }
}

sensor_msgs::ImagePtr toImageMsg(const cv::Mat& mat, const std::string& encoding, const std_msgs::Header& header) {
  return cv_bridge::CvImage(header, encoding, mat).toImageMsg();
}

OutputImage::OutputImage(const std_msgs::Header& header, int rows, int cols, int type, const std::string& encoding)
    : msg_(new sensor_msgs::Image) {
  msg_->header = header;
  msg_->height = rows;
  msg_->width = cols;
  msg_->encoding = encoding;
  msg_->is_bigendian = false;
  msg_->step = static_cast<uint32_t>(cols * CV_ELEM_SIZE(type));
  msg_->data.resize(static_cast<size_t>(msg_->step) * rows);
  mat_ = cv::Mat(rows, cols, type, msg_->data.data(), msg_->step);
}

sensor_msgs::ImagePtr OutputImage::finish() {
  if (mat_.data != msg_->data.data()) {
    // Reallocated by an OpenCV call: take its result the slow way.
    return toImageMsg(mat_, msg_->encoding, msg_->header);
  }
  return msg_;
}

}  // namespace blocks
}  // namespace imagenets
