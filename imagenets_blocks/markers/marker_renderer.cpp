// The marker image generator of the paper's Fig. 5.1 as a block: the marker at the world origin,
// a virtual camera (the input camera_info) at distance / pan / tilt looking at it.
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>

#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/blocks/image.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/frames.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/vision/marker_scene.h"
#include "imagenets/vision/target.h"
#include "imagenets/register_block.h"
#include "camera_ports.h"

namespace imagenets {
namespace blocks {

class MarkerRenderer : public Block {
 public:
  MarkerRenderer() {
    addInput<sensor_msgs::CameraInfo>("camera_info", "the virtual camera (size, K, D)");
    addOutput<sensor_msgs::Image>("image", "rendered mono8 image");
    addOutput<sensor_msgs::CameraInfo>("camera_info", "the camera_info, stamped like the image");
    addOutput<geometry_msgs::PoseStamped>("ground_truth", "true marker pose in the camera frame");
    addProperty("marker", "", "square marker description YAML; empty: render AprilTag `apriltag_id`").path();
    addProperty("target", "", "target file (config/targets/: square marker, AprilTag(s), ChArUco board); "
                              "rendered instead of `marker` / `apriltag_id` when set").path();
    addProperty<int>("apriltag_id", 0, "tag36h11 id rendered when `marker` is empty").range(0, 586);
    addProperty<double>("apriltag_size", 0.06, "AprilTag black-border edge, metres").range(0.001, 10.0);
    addProperty<double>("distance", 0.6, "camera to marker centre, metres").range(0.01, 100.0);
    addProperty<double>("pan", 0.0, "degrees about the marker normal").range(-360.0, 360.0);
    addProperty<double>("tilt", 0.0, "degrees away from the marker normal (0 = head-on)").range(0.0, 89.0);
    addProperty<double>("illumination", 1.0, "scene brightness (1 = nominal)").range(0.0, 100.0);
    addProperty<std::vector<double>>("light_direction", {0.3, 0.4, -1.0}, "direction the light travels, marker frame");
    addProperty<double>("ambient", 0.4, "ambient share of the light").range(0.0, 10.0);
    addProperty<double>("diffuse", 0.6, "directional (Lambertian) share of the light").range(0.0, 10.0);
    addProperty<double>("background", 0.5, "wall level behind the marker (0..1)").range(0.0, 1.0);
    addProperty<double>("blur", 0.7, "optical blur sigma, pixels").range(0.0, 20.0);
    addProperty<double>("noise", 2.0, "sensor noise sigma, gray levels").range(0.0, 100.0);
    addProperty<int>("seed", 1, "noise seed").range(0, 1 << 30);
    addProperty<int>("supersampling", 4, "n x n rays per pixel (anti-aliasing)").range(1, 8);
    addProperty<double>("paper", 0.85, "reflectance of the white paper").range(0.0, 1.0);
    addProperty<double>("ink", 0.10, "reflectance of the black ink").range(0.0, 1.0);
    addProperty("frame_id", "camera_optical_frame", "frame_id of the outputs");
  }

  void process(Context& ctx) override {
    const auto info = ctx.input<sensor_msgs::CameraInfo>("camera_info");
    const render::CameraModel camera = inputCameraModel(ctx, "camera_info");
    const std::string marker_path = ctx.property<std::string>("marker");
    render::Plane plane;
    const std::string target_path = ctx.property<std::string>("target");
    try {
      if (!target_path.empty()) {
        plane = target::TargetDescription::loadCached(target_path)->plane(Eigen::Isometry3d::Identity());
      } else if (!marker_path.empty()) {
        plane = marker::markerPlane(*marker::MarkerDescription::loadCached(marker_path), Eigen::Isometry3d::Identity());
      } else {
        marker::AprilTagOptions options;
        options.size = ctx.property<double>("apriltag_size");
        plane = marker::aprilTagPlane(options, ctx.property<int>("apriltag_id"), 0.25, Eigen::Isometry3d::Identity());
      }
    } catch (const std::exception& e) {
      throw BlockError(std::string(target_path.empty() ? "property 'marker': " : "property 'target': ") + e.what());
    }
    const double ink = ctx.property<double>("ink"), paper = ctx.property<double>("paper");
    if (!(ink < paper)) throw BlockError("property 'ink': must be below 'paper'");
    marker::applyPrintReflectance(&plane, paper, ink);
    const auto light = ctx.property<std::vector<double>>("light_direction");
    if (light.size() != 3) throw BlockError("property 'light_direction': needs 3 values, got " + std::to_string(light.size()));
    marker::ViewSettings view;
    view.distance = ctx.property<double>("distance");
    view.pan = ctx.property<double>("pan") * M_PI / 180.0;
    view.tilt = ctx.property<double>("tilt") * M_PI / 180.0;
    view.illumination = ctx.property<double>("illumination");
    view.light_direction = Eigen::Vector3d(light[0], light[1], light[2]);
    view.ambient = ctx.property<double>("ambient");
    view.diffuse = ctx.property<double>("diffuse");
    view.background = ctx.property<double>("background");
    view.blur = ctx.property<double>("blur");
    view.noise = ctx.property<double>("noise");
    view.seed = static_cast<std::uint64_t>(ctx.property<int>("seed"));
    const auto renderer = marker::sharedRenderer(camera, ctx.property<int>("supersampling"));
    Eigen::Isometry3d truth;
    const cv::Mat image = marker::renderView(*renderer, plane, view, &truth);

    std_msgs::Header header = info->header;
    header.frame_id = ctx.property<std::string>("frame_id");
    ctx.output("image", toImageMsg(image, "mono8", header));
    auto info_out = boost::make_shared<sensor_msgs::CameraInfo>(*info);
    info_out->header = header;
    ctx.output("camera_info", info_out);
    auto pose = boost::make_shared<geometry_msgs::PoseStamped>();
    pose->header = header;
    pose->pose = frames::toPose(truth);
    ctx.output("ground_truth", pose);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MarkerRenderer, "imagenets/MarkerRenderer", "markers",
                         "Renders a marker seen by a virtual camera (paper Fig. 5.1) with its true pose");
