#include "target_detector_block.h"

#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/marker_msgs.h"
#include "marker_ports.h"

namespace imagenets {
namespace blocks {

namespace {

std::string typeNames(const std::set<target::TargetType>& types) {
  std::string out;
  for (auto t : types) {
    target::TargetDescription d;
    d.type = t;
    out += (out.empty() ? "" : " or ") + d.typeName();
  }
  return out;
}

}  // namespace

TargetDetectorBlock::TargetDetectorBlock(std::set<target::TargetType> types) : types_(std::move(types)) {
  addInput<sensor_msgs::Image>("gray", "mono8 image");
  addInput<sensor_msgs::CameraInfo>("camera_info", "camera model of the image (K, D; lens distortion is used; a roi: the region)");
  addOptionalInput<geometry_msgs::PoseStamped>(
      "pose_hint", "expected target pose in the camera frame: picks the planar pose when both fit alike");
  addOutput<imagenets::MarkerDetection>("detection", "every corner found with its id and its point on the target; the pose");
  addOutput<std_msgs::Float64>("confidence", "in [0, 1] (AprilTag: decision margin / 100; ChArUco: share of the corners); only when found");
  addOutput<std_msgs::Float64>("reprojection_error", "RMS of the pose fit, pixels; only when found");
  addOutput<geometry_msgs::PoseStamped>("pose", "target pose in the camera frame (x right, y up, z out); only when found");
  addProperty("target", "", "target file (config/targets/NAME.yaml): " + typeNames(types_)).path();
  addProperty<double>("quad_decimate", 1.0, "AprilTag: libapriltag's quad_decimate (speed vs. small tags)").range(1.0, 8.0);
  addProperty<bool>("refine_edges", true, "AprilTag: locate each tag's black square again with the square marker's edge fit");
  addProperty<int>("min_corners", 4, "fewer corners found: not found").range(4, 100000);
}

std::shared_ptr<const target::TargetDescription> TargetDetectorBlock::loadTarget(const std::string& path) const {
  if (path.empty()) throw BlockError("property 'target': no target file set");
  std::shared_ptr<const target::TargetDescription> t;
  try {
    t = target::TargetDescription::loadCached(path);
  } catch (const std::exception& e) {
    throw BlockError(std::string("property 'target': ") + e.what());
  }
  if (!types_.count(t->type)) {
    throw BlockError("property 'target': " + path + " is a " + t->typeName() + " target; this block detects " +
                     typeNames(types_) + (t->type == target::TargetType::SquareMarker
                                              ? " (a square marker: imagenets/SquareMarkerDetector behind a threshold)"
                                              : ""));
  }
  return t;
}

// A bad target file is a load error naming the block, not a target never found.
void TargetDetectorBlock::configure() {
  if (!property<std::string>("target").empty()) loadTarget(property<std::string>("target"));
}

void TargetDetectorBlock::process(Context& ctx) {
  std_msgs::Header header;
  const cv::Mat gray = inputImage(ctx, "gray", {"mono8"}, nullptr, &header);
  cv::Point2d offset;
  const render::CameraModel camera = marker::inputCameraModel(ctx, gray, &offset);
  const auto t = loadTarget(ctx.property<std::string>("target"));
  target::TargetDetectorOptions options;
  options.quad_decimate = ctx.property<double>("quad_decimate");
  options.refine_edges = ctx.property<bool>("refine_edges");
  options.min_corners = ctx.property<int>("min_corners");
  Eigen::Isometry3d hint;
  options.pose_hint = marker::inputPoseHint(ctx, &hint);
  target::TargetDetection d = target::detectTarget(gray, camera, *t, options);
  marker::shiftPoints(d, offset);
  ctx.output("detection", marker::toMsg(d, t->name, header));
  marker::outputConfidenceAndPose(ctx, d.found, d.confidence, d.pose, header);
  marker::outputReprojectionError(ctx, d.found, d.reprojection_error);
}

}  // namespace blocks
}  // namespace imagenets
