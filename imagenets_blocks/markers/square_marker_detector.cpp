// The square-marker detector block of the robust marker detection net (paper Fig. 3.3).
#include <limits>

#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/blocks/image.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/register_block.h"
#include "marker_ports.h"

namespace imagenets {
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
    addProperty<int>("decimate", 1,
                     "outlines of dark regions traced on every n-th pixel and row of the thresholded image "
                     "(faster on large, noisy images; corners are still located on the gray image)")
        .range(1, 8);
    addProperty<double>("min_side_of_hint", 0.0,
                        "with a pose hint: quadrilaterals whose shortest side is under this share of the hinted "
                        "marker's are not examined (0: all)")
        .range(0.0, 1.0);
    addProperty<double>("min_inner_side_px", 0.0,
                        "inner corners join the pose fit only when the inner square's sides are this long (px; 0: always)")
        .range(0.0, 10000.0);
    addProperty<bool>("edge_model", false,
                      "fit a blurred-edge model to every pixel along each outer edge (dim, noisy, blurred images)");
    addProperty<double>("edge_model_max_side_px", 0.0,
                        "the edge model only for markers whose every side is shorter (px; 0: any size)")
        .range(0.0, 100000.0);
    addProperty<std::vector<double>>("match_blur_px", std::vector<double>{},
                                     "image blurs (sigma, px) under which a rejected candidate's pattern is matched again "
                                     "(small, far, blurred markers); empty: sharp match only");
  }

  // An unreadable marker file is a load error naming the block, not a marker never found (the
  // detector often runs inside feedback trials, whose failures only mean "no score").
  void configure() override {
    if (!property<std::string>("marker").empty()) loadMarker(property<std::string>("marker"));
    checkedBlurs(property<std::vector<double>>("match_blur_px"));
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
    const std::shared_ptr<const marker::MarkerDescription> desc = loadMarker(path);
    marker::DetectorOptions options;
    options.min_confidence = ctx.property<double>("min_confidence");
    options.refine_passes = ctx.property<int>("refine_passes");
    options.decimate = ctx.property<int>("decimate");
    options.min_side_of_hint = ctx.property<double>("min_side_of_hint");
    options.min_inner_side_px = ctx.property<double>("min_inner_side_px");
    options.edge_model = ctx.property<bool>("edge_model");
    options.edge_model_max_side_px = ctx.property<double>("edge_model_max_side_px");
    options.match_blur_px = checkedBlurs(ctx.property<std::vector<double>>("match_blur_px"));
    Eigen::Isometry3d hint;
    options.pose_hint = marker::inputPoseHint(ctx, &hint);
    marker::Detection d = marker::detect(gray, binary, camera, *desc, options);
    marker::shiftPoints(d, offset);
    ctx.output("detection", marker::toMsg(d, *desc, header));
    marker::outputConfidenceAndPose(ctx, d, header);
    marker::outputReprojectionError(ctx, d.found, d.reprojection_error);
  }

 private:
  static std::vector<double> checkedBlurs(const std::vector<double>& blurs) {
    for (const double sigma : blurs) {
      if (!(sigma > 0 && sigma <= 5)) {
        throw BlockError("property 'match_blur_px': " + std::to_string(sigma) + " is not a blur in (0, 5] px");
      }
    }
    return blurs;
  }

  static std::shared_ptr<const marker::MarkerDescription> loadMarker(const std::string& path) {
    try {
      return marker::MarkerDescription::loadCached(path);
    } catch (const std::exception& e) {
      throw BlockError(std::string("property 'marker': ") + e.what());
    }
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::SquareMarkerDetector, "imagenets/SquareMarkerDetector", "markers",
                         "ARToolKit-style square marker: 8 points, confidence, pose (sub-pixel, distortion-aware)");
