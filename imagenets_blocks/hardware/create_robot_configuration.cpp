// "Create Robot" of the paper's Fig. 3.1: a robot configuration (joint angles) from a property.
#include <cmath>

#include <boost/make_shared.hpp>
#include <sensor_msgs/JointState.h>

#include "imagenets/blocks/robot.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

class CreateRobotConfiguration : public Block {
 public:
  CreateRobotConfiguration() {
    addOutput<sensor_msgs::JointState>("configuration", "joint names and target angles (rad)");
    addProperty<std::vector<double>>("angles", {-35, 63, 83, 79, -22, 74, 0},
                                     "joint angles in degrees, in the group's joint order (the paper's \"Angles\")");
    addProperty<std::string>("group", "arm", "joint group: the arm (7 joints) or the pan-tilt head (pan, tilt)")
        .choices({"arm", "head"});
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
  }

  void process(Context& ctx) override {
    const auto& d = robotDescription(ctx.property<std::string>("description"));
    const auto& chain = ctx.property<std::string>("group") == "arm" ? d.arm : d.head;
    const auto deg = ctx.property<std::vector<double>>("angles");
    std::vector<double> q;
    for (double a : deg) q.push_back(a * M_PI / 180.0);
    const std::string bad = chain.limitViolation(q);
    if (!bad.empty()) throw BlockError("property 'angles': " + bad);
    auto msg = boost::make_shared<sensor_msgs::JointState>();
    msg->name = chain.names();
    msg->position = q;
    ctx.output("configuration", msg);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::CreateRobotConfiguration, "imagenets/CreateRobotConfiguration", "hardware",
                         "A robot configuration (joint angles of the arm or the head) from a property");
