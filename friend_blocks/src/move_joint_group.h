// The common part of MoveArm and MoveHead: send a joint configuration to a MoveJoints action
// server and output what was reached. The two blocks differ only in their defaults and docs.
#pragma once

#include <sensor_msgs/JointState.h>

#include "imagenets/block.h"

namespace imagenets {
namespace blocks {

class MoveJointGroup : public Block {
 protected:
  MoveJointGroup(const std::string& target_doc, const std::string& default_action, const std::string& action_doc,
                 double default_motion_timeout);

 public:
  void process(Context& ctx) override;
};

}  // namespace blocks
}  // namespace imagenets
