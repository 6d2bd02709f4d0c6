// Reads a named frame/object from the robot's world model (run-time data of the system).
#include <boost/make_shared.hpp>
#include <geometry_msgs/PoseStamped.h>

#include "friend_msgs/WorldModelGet.h"
#include "imagenets/register_block.h"
#include "imagenets/blocks/ros_access.h"

namespace imagenets {
namespace blocks {

class WorldModelGet : public Block {
 public:
  WorldModelGet() {
    addOptionalInput<geometry_msgs::PoseStamped>("after", "read only after this (e.g. WorldModelSet.pose)");
    addOutput<geometry_msgs::PoseStamped>("pose", "the object's pose");
    addProperty<std::string>("name", "", "object name");
    addProperty<std::string>("service", "world_model/get", "WorldModelGet service");
    addProperty<double>("timeout", 2.0, "seconds to wait for the service").range(0.0, 600.0);
  }
  void process(Context& ctx) override {
    hardware::ensureRosNode();
    const std::string service = ros::names::resolve(ctx.property<std::string>("service"));
    const std::string name = ctx.property<std::string>("name");
    if (name.empty()) throw BlockError("property 'name' is empty");
    if (!ros::service::waitForService(service, ros::Duration(ctx.property<double>("timeout")))) {
      throw BlockError("world model service '" + service + "' not available (property timeout)");
    }
    friend_msgs::WorldModelGet srv;
    srv.request.name = name;
    if (!ros::service::call(service, srv)) throw BlockError("world model service '" + service + "' call failed");
    if (!srv.response.found) throw BlockError("property 'name': " + srv.response.message);
    ctx.output("pose", boost::make_shared<geometry_msgs::PoseStamped>(srv.response.pose));
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::WorldModelGet, "imagenets/WorldModelGet", "hardware",
                         "A named frame/object from the robot's world model");
