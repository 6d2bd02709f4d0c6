// ChArUco boards (OpenCV's aruco module; config/targets/): the chessboard corners found, with
// OpenCV's ids and their points on the board, and the pose fitted to all of them.
#include "imagenets/register_block.h"
#include "target_detector_block.h"

namespace imagenets {
namespace blocks {

class CharucoDetector : public TargetDetectorBlock {
 public:
  CharucoDetector() : TargetDetectorBlock({target::TargetType::Charuco}) {}
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CharucoDetector, "imagenets/CharucoDetector", "markers",
                         "ChArUco board (OpenCV aruco, a target file): chessboard corners with ids, pose");
