#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Crops a region of interest; a camera_info given with the image is adjusted to match (principal
// point shifted, size and roi set), so later 3D steps still use the right model.
class CropRoi : public Block {
 public:
  CropRoi() {
    addInput<sensor_msgs::Image>("image", "any image");
    addOptionalInput<sensor_msgs::CameraInfo>("camera_info", "model of the full image (optional)");
    addOutput<sensor_msgs::Image>("image", "the region, same encoding");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the model of the region (when camera_info is given)");
    addProperty<int>("x", 0, "left column of the region (pixels)").range(0, 100000);
    addProperty<int>("y", 0, "top row of the region (pixels)").range(0, 100000);
    addProperty<int>("width", 0, "region width (pixels); 0: to the right edge").range(0, 100000);
    addProperty<int>("height", 0, "region height (pixels); 0: to the bottom edge").range(0, 100000);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {}, &encoding, &header);
    const int x = ctx.property<int>("x"), y = ctx.property<int>("y");
    const int w = ctx.property<int>("width") > 0 ? ctx.property<int>("width") : in.cols - x;
    const int h = ctx.property<int>("height") > 0 ? ctx.property<int>("height") : in.rows - y;
    const cv::Rect roi(x, y, w, h);
    if (w <= 0 || h <= 0 || (roi & cv::Rect(0, 0, in.cols, in.rows)) != roi) {
      throw BlockError("region x " + std::to_string(x) + ", y " + std::to_string(y) + ", " + std::to_string(w) + "x" +
                       std::to_string(h) + " is not inside the " + std::to_string(in.cols) + "x" +
                       std::to_string(in.rows) + " input 'image'");
    }
    if (auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info")) {
      if (info->width != static_cast<unsigned>(in.cols) || info->height != static_cast<unsigned>(in.rows)) {
        throw BlockError("input 'camera_info' is for " + std::to_string(info->width) + "x" +
                         std::to_string(info->height) + " images, input 'image' is " + std::to_string(in.cols) + "x" +
                         std::to_string(in.rows));
      }
      sensor_msgs::CameraInfo::Ptr out(new sensor_msgs::CameraInfo(*info));
      out->header = header;
      out->width = w;
      out->height = h;
      out->K[2] -= x;
      out->K[5] -= y;
      out->P[2] -= x;
      out->P[6] -= y;
      out->roi = sensor_msgs::RegionOfInterest();  // the image now is the region
      ctx.output("camera_info", out);
    }
    OutputImage out = newOutputImage(cv::Size(w, h), in.type(), encoding, header);
    in(roi).copyTo(out.mat);
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CropRoi, "imagenets/CropRoi", "preprocessing",
                         "Crops a region of interest (camera_info adjusted)");
