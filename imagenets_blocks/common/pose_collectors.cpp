// Collections of repeated frames and poses (collectors.h): a repeated sub-net's frame or pose
// output also comes as a geometry_msgs/PoseArray of its N results (`<port>_all`), in repetition
// order with the header of the last, for MeanRotation and MedianTranslation (paper Fig. 4.3).
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>

#include "imagenets/vision/frames.h"
#include "imagenets/collectors.h"

namespace imagenets {
namespace blocks {
namespace {

template <class Item, class ToPose>
boost::shared_ptr<geometry_msgs::PoseArray> collectPoses(const std::vector<boost::shared_ptr<const Item>>& items,
                                                         ToPose toPose) {
  auto poses = boost::make_shared<geometry_msgs::PoseArray>();
  for (const auto& item : items) {
    poses->header = item->header;
    poses->poses.push_back(toPose(*item));
  }
  return poses;
}

CollectorRegistration<geometry_msgs::TransformStamped, geometry_msgs::PoseArray> frames_collector(
    [](const std::vector<geometry_msgs::TransformStamped::ConstPtr>& items) {
      return collectPoses(items, [](const geometry_msgs::TransformStamped& t) { return frames::toPose(t.transform); });
    });

CollectorRegistration<geometry_msgs::PoseStamped, geometry_msgs::PoseArray> poses_collector(
    [](const std::vector<geometry_msgs::PoseStamped::ConstPtr>& items) {
      return collectPoses(items, [](const geometry_msgs::PoseStamped& p) { return p.pose; });
    });

}  // namespace
}  // namespace blocks
}  // namespace imagenets
