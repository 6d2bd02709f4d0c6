#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/render.h"
#include "imagenets/register_block.h"
#include "camera_ports.h"

namespace imagenets {
namespace blocks {

// Crops the region where an object is expected: its predicted pose in the camera frame projected
// into the image, its size plus a margin on each side (render::CameraModel::regionAround). The
// camera_info goes out with that region as its `roi` (K stays the full image's, as ROS defines
// roi), so a detector reports full-image points. Without a pose: the whole image.
class CropAroundPose : public Block {
 public:
  CropAroundPose() {
    addInput<sensor_msgs::Image>("image", "any image");
    addInput<sensor_msgs::CameraInfo>("camera_info", "camera model of the image");
    addOptionalInput<geometry_msgs::PoseStamped>("pose", "predicted object pose in the camera frame");
    addOutput<sensor_msgs::Image>("image", "the region, same encoding");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the input's, with `roi` set to the region");
    addProperty<double>("size", 0.06, "object size (metres) added to the region").range(0.0, 100.0);
    addProperty<int>("margin_px", 120, "pixels around the object on each side (0: the whole image)")
        .range(0, 100000);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {}, &encoding, &header);
    const auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
    const render::CameraModel camera = inputCameraModel(ctx, "camera_info");
    if (info->roi.width > 0 || info->roi.height > 0) {
      throw BlockError("input 'camera_info' already describes a region (roi " + std::to_string(info->roi.width) + "x" +
                       std::to_string(info->roi.height) + "); crop the full image");
    }
    if (in.cols != camera.width || in.rows != camera.height) {
      throw BlockError("input 'image' is " + std::to_string(in.cols) + "x" + std::to_string(in.rows) +
                       ", input 'camera_info' is for " + std::to_string(camera.width) + "x" +
                       std::to_string(camera.height) + " images");
    }
    cv::Rect region(0, 0, in.cols, in.rows);
    if (const auto pose = ctx.input<geometry_msgs::PoseStamped>("pose")) {
      const Eigen::Vector3d p(pose->pose.position.x, pose->pose.position.y, pose->pose.position.z);
      region = camera.regionAround(p, ctx.property<double>("size"), ctx.property<int>("margin_px"));
    }
    sensor_msgs::CameraInfo::Ptr out_info(new sensor_msgs::CameraInfo(*info));
    out_info->header = header;
    out_info->roi.x_offset = region.x;
    out_info->roi.y_offset = region.y;
    out_info->roi.width = region.width;
    out_info->roi.height = region.height;
    OutputImage out = newOutputImage(region.size(), in.type(), encoding, header);
    in(region).copyTo(out.mat);
    ctx.output("image", out.msg);
    ctx.output("camera_info", out_info);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CropAroundPose, "imagenets/CropAroundPose", "preprocessing",
                         "Crops where an object's predicted pose projects (camera_info roi set)");
