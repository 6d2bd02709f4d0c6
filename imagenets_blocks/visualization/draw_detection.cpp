#include <cstdio>

#include <imagenets/MarkerDetection.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/vision/frames.h"
#include "imagenets/blocks/image.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Draws a marker detection on its image (paper Fig. 3.3): the outer and inner corner quadrilaterals,
// the marker name and confidence, and, with the camera model, the marker's pose as axes (x red,
// y green, z blue) projected through the lens model. A detection that was not found is written as
// such.
class DrawDetection : public Block {
 public:
  DrawDetection() {
    addInput<sensor_msgs::Image>("image", "the image the detection comes from (mono8, bgr8, rgb8)");
    addInput<imagenets::MarkerDetection>("detection", "a marker detection of that image");
    addOptionalInput<sensor_msgs::CameraInfo>("camera_info", "camera model: draws the pose axes when given");
    addOutput<sensor_msgs::Image>("image", "bgr8 with the overlay");
    addProperty<double>("axis_length", 0.03, "length of the drawn pose axes (m)").range(0.0001, 10);
    addProperty<int>("thickness", 2, "line width (pixels)").range(1, 20);
  }

  void process(Context& ctx) override {
    std::string encoding;
    std_msgs::Header header;
    const cv::Mat in = inputImage(ctx, "image", {"mono8", "bgr8", "rgb8"}, &encoding, &header);
    auto det = ctx.input<imagenets::MarkerDetection>("detection");
    if (!det) throw BlockError("input 'detection': missing");
    OutputImage out = newOutputImage(in.size(), CV_8UC3, "bgr8", header);
    if (encoding == "mono8") cv::cvtColor(in, out.mat, cv::COLOR_GRAY2BGR);
    else if (encoding == "rgb8") cv::cvtColor(in, out.mat, cv::COLOR_RGB2BGR);
    else in.copyTo(out.mat);
    const int thickness = ctx.property<int>("thickness");
    const cv::Scalar green(0, 220, 0), yellow(0, 220, 255), red(0, 0, 255);
    if (!det->found) {
      cv::putText(out.mat, det->marker + ": not found", {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.7, red, 2, cv::LINE_AA);
      ctx.output("image", out.msg);
      return;
    }
    const int shift = 4;
    std::vector<cv::Point> pts;
    for (const auto& p : det->points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw BlockError("input 'detection': a point is not finite");
      pts.emplace_back(cvRound(p.x * (1 << shift)), cvRound(p.y * (1 << shift)));
    }
    for (size_t q = 0; q + 4 <= pts.size(); q += 4) {
      std::vector<cv::Point> quad(pts.begin() + q, pts.begin() + q + 4);
      cv::polylines(out.mat, quad, true, q == 0 ? green : yellow, thickness, cv::LINE_AA, shift);
    }
    if (!pts.empty()) {
      cv::circle(out.mat, pts[0], 5 << shift, red, cv::FILLED, cv::LINE_AA, shift);  // the first (top-left) corner
      char text[128];
      std::snprintf(text, sizeof text, "%s %.2f", det->marker.c_str(), det->confidence);
      cv::putText(out.mat, text, cv::Point(pts[0].x >> shift, pts[0].y >> shift) + cv::Point(6, -8),
                  cv::FONT_HERSHEY_SIMPLEX, 0.6, green, 2, cv::LINE_AA);
    }
    if (auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info")) {
      if (info->K[0] <= 0 || info->K[4] <= 0) throw BlockError("input 'camera_info': K has no focal length");
      Eigen::Isometry3d pose;
      try {
        pose = frames::toIsometry(det->pose, "input 'detection' pose");
      } catch (const frames::FrameError& e) {
        throw BlockError(e.what());
      }
      const double l = ctx.property<double>("axis_length");
      std::vector<cv::Point3d> axes;
      for (const Eigen::Vector3d& v : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(l, 0, 0), Eigen::Vector3d(0, l, 0),
                                       Eigen::Vector3d(0, 0, l)}) {
        const Eigen::Vector3d c = pose * v;
        if (c.z() <= 0) throw BlockError("input 'detection': pose is behind the camera");
        axes.emplace_back(c.x(), c.y(), c.z());
      }
      std::vector<cv::Point2d> image_points;
      const cv::Matx33d K(info->K.data());
      const cv::Mat D = info->distortion_model == "equidistant" ? cv::Mat() : cv::Mat(info->D, true);
      cv::projectPoints(axes, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, image_points);
      const cv::Scalar colours[3] = {{0, 0, 255}, {0, 255, 0}, {255, 0, 0}};
      auto fixed = [&](const cv::Point2d& p) { return cv::Point(cvRound(p.x * (1 << shift)), cvRound(p.y * (1 << shift))); };
      for (int a = 0; a < 3; ++a) {
        cv::line(out.mat, fixed(image_points[0]), fixed(image_points[a + 1]), colours[a], thickness, cv::LINE_AA, shift);
      }
    }
    ctx.output("image", out.msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::DrawDetection, "imagenets/DrawDetection", "visualization",
                         "Draws a marker detection (corners, confidence, pose axes) on its image");
