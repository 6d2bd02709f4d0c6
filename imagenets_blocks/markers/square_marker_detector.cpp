// The square-marker detector block of the robust marker detection net (paper Fig. 3.3).
#include <limits>

#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/blocks/marker_msgs.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace marker {

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& pose) {
  geometry_msgs::Pose p;
  p.position.x = pose.translation().x();
  p.position.y = pose.translation().y();
  p.position.z = pose.translation().z();
  const Eigen::Quaterniond q(pose.linear());
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  p.orientation.w = q.w();
  return p;
}

Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return T;
}

imagenets::MarkerDetectionPtr toMsg(const Detection& d, const std::string& marker_name, const std_msgs::Header& header) {
  auto msg = boost::make_shared<imagenets::MarkerDetection>();
  msg->header = header;
  msg->marker = marker_name;
  msg->found = d.found;
  msg->confidence = d.confidence;
  msg->threshold = std::numeric_limits<double>::quiet_NaN();
  if (d.found) {
    for (const auto& p : d.points) {
      geometry_msgs::Point q;
      q.x = p.x;
      q.y = p.y;
      msg->points.push_back(q);
    }
    msg->pose = toPoseMsg(d.pose);
    msg->alternative_pose = toPoseMsg(d.alt_pose);
    msg->reprojection_error = d.reprojection_error;
    msg->alternative_reprojection_error = d.alt_reprojection_error;
  } else {
    msg->pose.orientation.w = msg->alternative_pose.orientation.w = 1.0;
  }
  return msg;
}

render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray, cv::Point2d* offset) {
  const auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
  if (!info) throw BlockError("input 'camera_info': missing");
  render::CameraModel camera;
  try {
    camera = render::CameraModel::fromCameraInfo(*info);
  } catch (const std::exception& e) {
    throw BlockError(std::string("input 'camera_info': ") + e.what());
  }
  const sensor_msgs::RegionOfInterest& roi = info->roi;
  if (roi.width > 0 && roi.height > 0) {
    const cv::Rect region(roi.x_offset, roi.y_offset, roi.width, roi.height);
    if ((region & cv::Rect(0, 0, camera.width, camera.height)) != region) {
      throw BlockError("input 'camera_info': roi " + std::to_string(roi.width) + "x" + std::to_string(roi.height) +
                       " at " + std::to_string(roi.x_offset) + "," + std::to_string(roi.y_offset) +
                       " is not inside the " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                       " image");
    }
    camera = camera.cropped(region);
    if (offset) *offset = cv::Point2d(roi.x_offset, roi.y_offset);
  } else if (offset) {
    *offset = cv::Point2d(0, 0);
  }
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw BlockError("input 'gray': image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                     " but camera_info is " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                     (roi.width > 0 && roi.height > 0 ? " (its roi)" : ""));
  }
  return camera;
}

void shiftPoints(Detection& d, const cv::Point2d& offset) {
  if (!d.found) return;
  for (auto& p : d.points) p += offset;
}

void outputConfidenceAndPose(Context& ctx, const Detection& d, const std_msgs::Header& header) {
  if (!d.found) return;
  auto score = boost::make_shared<std_msgs::Float64>();
  score->data = d.confidence;
  ctx.output("confidence", score);
  auto pose = boost::make_shared<geometry_msgs::PoseStamped>();
  pose->header = header;
  pose->pose = toPoseMsg(d.pose);
  ctx.output("pose", pose);
}

}  // namespace marker

namespace blocks {

// Finds the square marker in a thresholded image; refines its corners on the gray image.
// Outputs `confidence`, `reprojection_error` and `pose` only when the marker is found: a feedback
// sweep then records "no score" (NaN in the trace) for a threshold at which the marker is not
// found, and the engine reports "no valid candidate" when no threshold finds it. `detection` is
// always output. On a region of the image (camera_info with a roi) the points are full-image pixels.
class SquareMarkerDetector : public Block {
 public:
  SquareMarkerDetector() {
    addInput<sensor_msgs::Image>("image", "thresholded image, mono8 (marker border dark = 0)");
    addInput<sensor_msgs::Image>("gray", "the gray image (mono8) the corners are refined on");
    addInput<sensor_msgs::CameraInfo>("camera_info", "camera model of the images (K, D; lens distortion is used)");
    addOptionalInput<geometry_msgs::PoseStamped>(
        "pose_hint", "expected marker pose in the camera frame: picks the planar pose when both fit alike");
    addOutput<imagenets::MarkerDetection>("detection", "8 defined points, confidence, pose (both IPPE solutions)");
    addOutput<std_msgs::Float64>("confidence", "pattern match in [0, 1]; only when found (feedback score)");
    addOutput<std_msgs::Float64>("reprojection_error", "RMS of the pose fit, pixels; only when found");
    addOutput<geometry_msgs::PoseStamped>("pose", "marker pose in the camera frame; only when found");
    addProperty("marker", "", "marker description YAML (config/markers/NAME.yaml)").path();
    addProperty<double>("min_confidence", 0.5, "pattern match below which the marker counts as not found")
        .range(0.0, 1.0);
    addProperty<int>("refine_passes", 2, "sub-pixel edge refinement passes on the gray image (0: pixel corners)")
        .range(0, 10);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat binary = inputImage(ctx, "image", {"mono8"});
    const cv::Mat gray = inputImage(ctx, "gray", {"mono8"}, nullptr, &header);
    cv::Point2d offset;
    const render::CameraModel camera = marker::inputCameraModel(ctx, gray, &offset);
    if (binary.size() != gray.size()) throw BlockError("input 'image': size differs from input 'gray'");
    const std::string path = ctx.property<std::string>("marker");
    if (path.empty()) throw BlockError("property 'marker': no marker file set");
    std::shared_ptr<const marker::MarkerDescription> desc;
    try {
      desc = marker::MarkerDescription::loadCached(path);
    } catch (const std::exception& e) {
      throw BlockError(std::string("property 'marker': ") + e.what());
    }
    marker::DetectorOptions options;
    options.min_confidence = ctx.property<double>("min_confidence");
    options.refine_passes = ctx.property<int>("refine_passes");
    Eigen::Isometry3d hint;
    if (const auto pose_hint = ctx.input<geometry_msgs::PoseStamped>("pose_hint")) {
      hint = marker::fromPoseMsg(pose_hint->pose);
      options.pose_hint = &hint;
    }
    marker::Detection d = marker::detect(gray, binary, camera, *desc, options);
    marker::shiftPoints(d, offset);
    ctx.output("detection", marker::toMsg(d, desc->name, header));
    marker::outputConfidenceAndPose(ctx, d, header);
    if (d.found) {
      auto error = boost::make_shared<std_msgs::Float64>();
      error->data = d.reprojection_error;
      ctx.output("reprojection_error", error);
    }
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SquareMarkerDetector, "imagenets/SquareMarkerDetector", "markers",
                         "ARToolKit-style square marker: 8 points, confidence, pose (sub-pixel, distortion-aware)");
