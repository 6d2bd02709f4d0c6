// The square-marker detector block of the robust marker detection net (paper Fig. 3.3).
#include <limits>

#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/blocks/marker_msgs.h"
#include "imagenets/register_block.h"

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

render::CameraModel inputCameraModel(const Context& ctx, const cv::Mat& gray) {
  const auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
  if (!info) throw BlockError("input 'camera_info': missing");
  render::CameraModel camera;
  try {
    camera = render::CameraModel::fromCameraInfo(*info);
  } catch (const std::exception& e) {
    throw BlockError(std::string("input 'camera_info': ") + e.what());
  }
  if (gray.cols != camera.width || gray.rows != camera.height) {
    throw BlockError("input 'gray': image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                     " but camera_info is " + std::to_string(camera.width) + "x" + std::to_string(camera.height));
  }
  return camera;
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
// Outputs `confidence` and `pose` only when the marker is found: a feedback sweep then records
// "no score" (NaN in the trace) for a threshold at which the marker is not found, and the engine
// reports "no valid candidate" when no threshold finds it. `detection` is always output.
class SquareMarkerDetector : public Block {
 public:
  SquareMarkerDetector() {
    addInput<sensor_msgs::Image>("image", "thresholded image, mono8 (marker border dark = 0)");
    addInput<sensor_msgs::Image>("gray", "the gray image (mono8) the corners are refined on");
    addInput<sensor_msgs::CameraInfo>("camera_info", "camera model of the images (K, D; lens distortion is used)");
    addOutput<imagenets::MarkerDetection>("detection", "8 defined points, confidence, pose (both IPPE solutions)");
    addOutput<std_msgs::Float64>("confidence", "pattern match in [0, 1]; only when found (feedback score)");
    addOutput<geometry_msgs::PoseStamped>("pose", "marker pose in the camera frame; only when found");
    addProperty("marker", "", "marker description YAML (config/markers/NAME.yaml)").path();
    addProperty<double>("min_confidence", 0.5, "pattern match below which the marker counts as not found")
        .range(0.0, 1.0);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat binary = inputImage(ctx, "image", {"mono8"});
    const cv::Mat gray = inputImage(ctx, "gray", {"mono8"}, nullptr, &header);
    const render::CameraModel camera = marker::inputCameraModel(ctx, gray);
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
    const marker::Detection d = marker::detect(gray, binary, camera, *desc, options);
    ctx.output("detection", marker::toMsg(d, desc->name, header));
    marker::outputConfidenceAndPose(ctx, d, header);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SquareMarkerDetector, "imagenets/SquareMarkerDetector", "markers",
                         "ARToolKit-style square marker: 8 points, confidence, pose (sub-pixel, distortion-aware)");
