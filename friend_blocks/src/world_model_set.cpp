// Stores a named frame/object in the robot's world model.
#include <geometry_msgs/PoseStamped.h>

#include "friend_msgs/WorldModelSet.h"
#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class WorldModelSet : public Block {
 public:
  WorldModelSet() {
    addInput<geometry_msgs::PoseStamped>("pose", "the object's pose (empty frame_id: robot base)");
    addOutput<geometry_msgs::PoseStamped>("pose", "the stored pose (passed through once stored)");
    addProperty<std::string>("name", "", "object name");
    addProperty<std::string>("description", "", "free text stored with the object");
    addProperty<std::string>("service", "world_model/set", "WorldModelSet service");
    addProperty<double>("timeout", 2.0, "seconds to wait for the service").range(0.0, 600.0);
  }
  void process(Context& ctx) override {
    hardware::ensureRosNode();
    const std::string service = ros::names::resolve(ctx.property<std::string>("service"));
    friend_msgs::WorldModelSet srv;
    srv.request.name = ctx.property<std::string>("name");
    if (srv.request.name.empty()) throw BlockError("property 'name' is empty");
    srv.request.pose = *ctx.input<geometry_msgs::PoseStamped>("pose");
    srv.request.description = ctx.property<std::string>("description");
    if (!ros::service::waitForService(service, ros::Duration(ctx.property<double>("timeout")))) {
      throw BlockError("world model service '" + service + "' not available (property timeout)");
    }
    if (!ros::service::call(service, srv)) throw BlockError("world model service '" + service + "' call failed");
    if (!srv.response.success) throw BlockError(srv.response.message);
    ctx.setOutput("pose", ctx.inputValue("pose"));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::WorldModelSet, "imagenets/WorldModelSet", "hardware",
                         "Stores a named frame/object in the robot's world model");
