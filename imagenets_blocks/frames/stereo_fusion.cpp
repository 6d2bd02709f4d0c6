#include <cmath>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Fuses the left and right camera's measurement of one frame (paper 4.2): the mean when both
// are present and agree, the present one when only one is, and no output (an error with the
// reason) when they disagree or neither is present.
class StereoFusion : public Block {
 public:
  StereoFusion() {
    addOptionalInput<geometry_msgs::TransformStamped>("first", "measurement 1 (e.g. left camera); absent = invalid");
    addOptionalInput<geometry_msgs::TransformStamped>("second", "measurement 2, same frames as `first`; absent = invalid");
    addOutput<geometry_msgs::TransformStamped>("frame", "the fused frame");
    addProperty<double>("max_position_difference", 0.01, "largest distance (m) between agreeing measurements")
        .range(0, 10);
    addProperty<double>("max_angle_difference", 0.0873, "largest rotation (rad) between agreeing measurements")
        .range(0, M_PI);
  }

  void process(Context& ctx) override {
    geometry_msgs::TransformStamped::ConstPtr first_msg, second_msg;
    std::optional<Eigen::Isometry3d> first, second;
    if (ctx.hasInput("first")) first = inputFrame(ctx, "first", &first_msg);
    if (ctx.hasInput("second")) second = inputFrame(ctx, "second", &second_msg);
    if (first_msg && second_msg && (first_msg->header.frame_id != second_msg->header.frame_id ||
                                    first_msg->child_frame_id != second_msg->child_frame_id)) {
      throw BlockError("inputs 'first' (" + first_msg->header.frame_id + " -> " + first_msg->child_frame_id +
                       ") and 'second' (" + second_msg->header.frame_id + " -> " + second_msg->child_frame_id +
                       ") are not the same frame");
    }
    frames::FusionLimits limits;
    limits.max_position_difference = ctx.property<double>("max_position_difference");
    limits.max_angle_difference = ctx.property<double>("max_angle_difference");
    const frames::FusionResult r = frames::fusePoses(first, second, limits);
    if (!r.valid) throw BlockError("no fused frame: " + r.reason);
    const auto& ref = first_msg ? first_msg : second_msg;
    std_msgs::Header header = ref->header;
    if (first_msg && second_msg) header.stamp = std::max(first_msg->header.stamp, second_msg->header.stamp);
    ctx.output("frame", frameMsg(r.pose, header, ref->child_frame_id));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::StereoFusion, "imagenets/StereoFusion", "frames",
                         "Fuses two measurements of a frame (mean if they agree, else the valid one)");
