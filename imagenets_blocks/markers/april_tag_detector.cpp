// The AprilTag detector block: libapriltag with its pose estimation, lens distortion handled.
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/blocks/image.h"
#include "imagenets/vision/marker_msgs.h"
#include "imagenets/register_block.h"
#include "marker_ports.h"

namespace imagenets {
namespace blocks {

// Outputs like SquareMarkerDetector (detection always; confidence and pose only when found), so
// the two are interchangeable in a net. The detection has the 4 outer corners only.
class AprilTagDetectorBlock : public Block {
 public:
  AprilTagDetectorBlock() {
    addInput<sensor_msgs::Image>("gray", "mono8 image");
    addInput<sensor_msgs::CameraInfo>("camera_info", "camera model (K, D; lens distortion is used)");
    addOutput<imagenets::MarkerDetection>("detection", "4 outer corners, confidence, pose (both solutions)");
    addOutput<std_msgs::Float64>("confidence", "decision margin / 100 in [0, 1]; only when found");
    addOutput<geometry_msgs::PoseStamped>("pose", "tag pose in the camera frame (x right, y up, z out); only when found");
    addProperty("family", "tag36h11", "tag family").choices({"tag36h11", "tag25h9", "tag16h5", "tagStandard41h12"});
    addProperty<int>("id", -1, "tag id to report; -1: the lowest id found").range(-1, 100000);
    addProperty<double>("size", 0.06, "outer edge of the black border, metres").range(0.001, 10.0);
    addProperty<double>("quad_decimate", 1.0, "libapriltag quad_decimate (speed vs. small tags)").range(1.0, 8.0);
  }

  void process(Context& ctx) override {
    std_msgs::Header header;
    const cv::Mat gray = inputImage(ctx, "gray", {"mono8"}, nullptr, &header);
    cv::Point2d offset;
    const render::CameraModel camera = marker::inputCameraModel(ctx, gray, &offset);
    marker::AprilTagOptions options;
    options.family = ctx.property<std::string>("family");
    options.id = ctx.property<int>("id");
    options.size = ctx.property<double>("size");
    options.quad_decimate = ctx.property<double>("quad_decimate");
    // libapriltag keeps state: a detector per call (cheap next to detection), never shared.
    const marker::AprilTagDetector detector(options);
    marker::Detection d = detector.detect(gray, camera);
    marker::shiftPoints(d, offset);
    auto msg = marker::toMsg(d, options.family + ":" + std::to_string(options.id), header);
    if (d.found) msg->points.resize(4);
    ctx.output("detection", msg);
    marker::outputConfidenceAndPose(ctx, d, header);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::AprilTagDetectorBlock, "imagenets/AprilTagDetector", "markers",
                         "libapriltag tag detection and pose (distortion-aware)");
