// AprilTag targets (one tag or a grid, any libapriltag family; config/targets/): every tag
// corner found, with its id and its point on the target, and the pose fitted to all of them.
#include "imagenets/register_block.h"
#include "target_detector_block.h"

namespace imagenets {
namespace blocks {

class AprilTagTargetDetector : public TargetDetectorBlock {
 public:
  AprilTagTargetDetector() : TargetDetectorBlock({target::TargetType::AprilTag}) {}
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::AprilTagTargetDetector, "imagenets/AprilTagTargetDetector", "markers",
                         "AprilTag target (one tag or a grid, a target file): corners with ids, pose");
