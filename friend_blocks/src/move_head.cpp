// Moves FRIEND's pan-tilt head (PTH) to pan and tilt angles through its friend_msgs/MoveJoints action server.
#include "imagenets/register_block.h"
#include "move_joint_group.h"

namespace imagenets {
namespace blocks {

class MoveHead : public MoveJointGroup {
 public:
  MoveHead()
      : MoveJointGroup("target pan and tilt (rad), by joint name", "head/move_joints",
                       "MoveJoints action server of the pan-tilt head", 60.0) {}
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MoveHead, "imagenets/MoveHead", "hardware",
                         "Moves the pan-tilt head to pan and tilt angles (actionlib MoveJoints)");
