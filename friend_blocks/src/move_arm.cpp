// Moves FRIEND's arm to a configuration through its friend_msgs/MoveJoints action server.
#include "imagenets/register_block.h"
#include "move_joint_group.h"

namespace imagenets {
namespace blocks {

class MoveArm : public MoveJointGroup {
 public:
  MoveArm()
      : MoveJointGroup("target joint names and angles (rad)", "arm/move_joints", "MoveJoints action server of the arm",
                       120.0) {}
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::MoveArm, "imagenets/MoveArm", "hardware",
                         "Moves the arm to a joint configuration (actionlib MoveJoints)");
