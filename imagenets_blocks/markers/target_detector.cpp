// Whichever printed target a target file describes (AprilTag or ChArUco): the block a net uses
// when the target is the user's choice, e.g. the calibration's target detection net.
#include "imagenets/register_block.h"
#include "target_detector_block.h"

namespace imagenets {
namespace blocks {

class TargetDetector : public TargetDetectorBlock {
 public:
  TargetDetector() : TargetDetectorBlock({target::TargetType::AprilTag, target::TargetType::Charuco}) {}
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::TargetDetector, "imagenets/TargetDetector", "markers",
                         "A printed target of a target file (AprilTag or ChArUco): corners with ids, pose");
