#include <geometry_msgs/Vector3Stamped.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Per-axis median of the positions of a set of poses: robust to outliers in any axis.
class MedianTranslation : public Block {
 public:
  MedianTranslation() {
    addInput<geometry_msgs::PoseArray>("poses", "the set (orientations are checked, then ignored)");
    addOutput<geometry_msgs::Vector3Stamped>("translation", "x, y, z medians taken independently (m)");
  }

  void process(Context& ctx) override {
    geometry_msgs::PoseArray::ConstPtr msg;
    std::vector<Eigen::Vector3d> positions;
    for (const auto& p : inputPoses(ctx, "poses", &msg)) positions.push_back(p.translation());
    geometry_msgs::Vector3Stamped::Ptr out(new geometry_msgs::Vector3Stamped);
    out->header = msg->header;
    out->vector = frames::toVector3Msg(frames::medianTranslation(positions));
    ctx.output("translation", out);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MedianTranslation, "imagenets/MedianTranslation", "frames",
                         "Per-axis median position of a pose set");
