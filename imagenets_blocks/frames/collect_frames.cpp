#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Gathers several frames of one parent into a set (geometry_msgs/PoseArray), e.g. the N
// measurements of a calibration frame for MeanRotation and MedianTranslation. Absent inputs are
// skipped; at least one must be present.
class CollectFrames : public Block {
 public:
  CollectFrames() {
    addProperty<int>("inputs", 3, "number of frame inputs frame_1..frame_N").range(1, 64);
    addOutput<geometry_msgs::PoseArray>("poses", "the present frames in input order, header of the first");
  }

  void configure() override {
    for (int i = 1; i <= property<int>("inputs"); ++i) {
      addOptionalInput<geometry_msgs::TransformStamped>("frame_" + std::to_string(i), "a frame; all with the same parent");
    }
  }

  void process(Context& ctx) override {
    geometry_msgs::PoseArray::Ptr out(new geometry_msgs::PoseArray);
    std::string first_port;
    for (const auto& port : inputs()) {
      if (!ctx.hasInput(port.name)) continue;
      geometry_msgs::TransformStamped::ConstPtr msg;
      const Eigen::Isometry3d t = inputFrame(ctx, port.name, &msg);
      if (first_port.empty()) {
        first_port = port.name;
        out->header = msg->header;
      } else if (msg->header.frame_id != out->header.frame_id) {
        throw BlockError("input '" + port.name + "' is in frame '" + msg->header.frame_id + "', input '" + first_port +
                         "' in '" + out->header.frame_id + "'");
      }
      out->poses.push_back(frames::toPose(t));
    }
    if (out->poses.empty()) throw BlockError("no input frame present");
    ctx.output("poses", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CollectFrames, "imagenets/CollectFrames", "frames",
                         "Gathers frames into a pose set (PoseArray)");
