// The target detector blocks (imagenets/AprilTagTargetDetector, imagenets/CharucoDetector,
// imagenets/TargetDetector): one block class, told which target types it takes. Ports as
// SquareMarkerDetector's, so that they replace it in a net: in gray + camera_info (+ pose_hint);
// out detection (always), confidence, reprojection_error and pose (only when found).
#pragma once

#include <set>
#include <string>

#include "imagenets/block.h"
#include "imagenets/vision/target.h"

namespace imagenets {
namespace blocks {

class TargetDetectorBlock : public Block {
 public:
  // `types`: the target types the block takes (the others are a load error naming the file).
  explicit TargetDetectorBlock(std::set<target::TargetType> types);
  void configure() override;
  void process(Context& ctx) override;

 private:
  std::shared_ptr<const target::TargetDescription> loadTarget(const std::string& path) const;
  const std::set<target::TargetType> types_;
};

}  // namespace blocks
}  // namespace imagenets
