#include <opencv2/imgcodecs.hpp>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"
#include "imagenets/time.h"

namespace imagenets {
namespace blocks {

// Reads an image file (PNG, JPEG, ...) and publishes it.
class ImageFileSource : public Block {
 public:
  ImageFileSource() {
    addOutput<sensor_msgs::Image>("image", "the image read from `path`");
    addProperty<std::string>("path", "", "image file; relative to the net file").path();
    addProperty<std::string>("encoding", "bgr8", "bgr8: colour, mono8: gray").choices({"bgr8", "mono8"});
    addProperty<std::string>("frame_id", "camera", "frame_id of the image header");
  }

  void process(Context& ctx) override {
    const auto path = ctx.property<std::string>("path");
    if (path.empty()) throw BlockError("property 'path' is empty");
    const bool mono = ctx.property<std::string>("encoding") == "mono8";
    cv::Mat image = cv::imread(path, mono ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
    if (image.empty()) throw BlockError("property 'path': cannot read image '" + path + "'");
    std_msgs::Header header;
    header.stamp = now();
    header.frame_id = ctx.property<std::string>("frame_id");
    ctx.output("image", toImageMsg(image, mono ? "mono8" : "bgr8", header));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ImageFileSource, "imagenets/ImageFileSource", "acquisition",
                         "Reads an image file");
