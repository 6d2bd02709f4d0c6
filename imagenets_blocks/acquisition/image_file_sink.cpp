#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Writes its input image to a file. Writes a temporary file and renames it, so a reader never
// sees a half-written image and a failure leaves the previous file intact.
class ImageFileSink : public Block {
 public:
  ImageFileSink() {
    addInput<sensor_msgs::Image>("image", "image to write (mono8, bgr8, rgb8, 16UC1, ...)");
    addProperty<std::string>("path", "", "output file; the extension selects the format").path();
  }

  void process(Context& ctx) override {
    const auto path = ctx.property<std::string>("path");
    if (path.empty()) throw BlockError("property 'path' is empty");
    std::string encoding;
    cv::Mat image = inputImage(ctx, "image", {}, &encoding);
    cv::Mat out = image;
    if (encoding == "rgb8") cv::cvtColor(image, out, cv::COLOR_RGB2BGR);
    const auto dot = path.rfind('.');
    const std::string tmp = path.substr(0, dot) + ".tmp" + (dot == std::string::npos ? "" : path.substr(dot));
    bool written = false;
    try {
      written = cv::imwrite(tmp, out);
    } catch (const cv::Exception& e) {
      std::remove(tmp.c_str());
      throw BlockError("cannot write '" + path + "': " + e.what());
    }
    if (!written || std::rename(tmp.c_str(), path.c_str()) != 0) {
      std::remove(tmp.c_str());
      throw BlockError("cannot write '" + path + "'");
    }
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ImageFileSink, "imagenets/ImageFileSink", "acquisition",
                         "Writes an image file");
