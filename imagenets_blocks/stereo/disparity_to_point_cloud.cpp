#include <cmath>

#include <sensor_msgs/CameraInfo.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/point_cloud.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// 3D points from a disparity image and the rectified camera models: with the left projection
// P_l (fx, fy, cx, cy) and the right one P_r (baseline B = -P_r[3] / fx, principal point cx_r),
//   Z = fx * B / (d - (cx - cx_r)),  X = (u - cx) Z / fx,  Y = (v - cy) Z / fy,
// in the left camera's optical frame (REP-103: z forward, x right, y down), coloured from the
// left image.
class DisparityToPointCloud : public Block {
 public:
  DisparityToPointCloud() {
    addInput<sensor_msgs::Image>("disparity", "32FC1 disparity (pixels) on the left image, NaN = unknown");
    addInput<sensor_msgs::CameraInfo>("left_info", "rectified left model (P used)");
    addInput<sensor_msgs::CameraInfo>("right_info", "rectified right model (P[3] = -fx * baseline)");
    addOptionalInput<sensor_msgs::Image>("image", "left image for colour (mono8, bgr8, rgb8; same size)");
    addOutput<sensor_msgs::PointCloud2>("cloud", "x, y, z (+ rgb) in the left optical frame, valid points only");
    addProperty<double>("min_depth", 0.1, "drop points nearer than this (m)").range(0, 1e6);
    addProperty<double>("max_depth", 20.0, "drop points farther than this (m)").range(0, 1e6);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat disparity = inputImage(ctx, "disparity", {"32FC1"}, nullptr, &header);
    auto left = ctx.input<sensor_msgs::CameraInfo>("left_info");
    auto right = ctx.input<sensor_msgs::CameraInfo>("right_info");
    if (!left) throw BlockError("input 'left_info': missing");
    if (!right) throw BlockError("input 'right_info': missing");
    if (left->width != static_cast<unsigned>(disparity.cols) || left->height != static_cast<unsigned>(disparity.rows)) {
      throw BlockError("input 'left_info' is for " + std::to_string(left->width) + "x" + std::to_string(left->height) +
                       " images, input 'disparity' is " + std::to_string(disparity.cols) + "x" +
                       std::to_string(disparity.rows));
    }
    const double fx = left->P[0], fy = left->P[5], cx = left->P[2], cy = left->P[6];
    if (fx <= 0 || fy <= 0) throw BlockError("input 'left_info': P has no focal length");
    if (right->P[0] <= 0) throw BlockError("input 'right_info': P has no focal length");
    const double baseline = -right->P[3] / right->P[0];
    if (!(baseline > 0)) {
      throw BlockError("input 'right_info': P[3] = " + std::to_string(right->P[3]) +
                       " gives no positive baseline (expected -fx * baseline)");
    }
    const double delta_cx = cx - right->P[2];
    cv::Mat colour;
    std::string encoding;
    if (ctx.hasInput("image")) {
      colour = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding);
      if (colour.size() != disparity.size()) {
        throw BlockError("input 'image' (" + std::to_string(colour.cols) + "x" + std::to_string(colour.rows) +
                         ") and input 'disparity' differ in size");
      }
    }
    const double min_z = ctx.property<double>("min_depth"), max_z = ctx.property<double>("max_depth");
    std::vector<cloud::PointXYZRGB> points;
    points.reserve(disparity.total() / 2);
    for (int v = 0; v < disparity.rows; ++v) {
      const float* d = disparity.ptr<float>(v);
      for (int u = 0; u < disparity.cols; ++u) {
        const double denom = d[u] - delta_cx;
        if (!std::isfinite(denom) || denom <= 0) continue;
        const double z = fx * baseline / denom;
        if (z < min_z || z > max_z) continue;
        cloud::PointXYZRGB p;
        p.x = static_cast<float>((u - cx) * z / fx);
        p.y = static_cast<float>((v - cy) * z / fy);
        p.z = static_cast<float>(z);
        p.r = p.g = p.b = 255;
        if (!colour.empty()) {
          if (encoding == "mono8") {
            p.r = p.g = p.b = colour.at<uchar>(v, u);
          } else {
            const cv::Vec3b c = colour.at<cv::Vec3b>(v, u);
            const bool rgb = encoding == "rgb8";
            p.r = rgb ? c[0] : c[2];
            p.g = c[1];
            p.b = rgb ? c[2] : c[0];
          }
        }
        points.push_back(p);
      }
    }
    auto out = cloud::makeCloud(points, !colour.empty());
    out->header = header;
    ctx.output("cloud", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::DisparityToPointCloud, "imagenets/DisparityToPointCloud", "stereo",
                         "3D point cloud (with colour) from disparity and camera models");
