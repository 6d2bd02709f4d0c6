#include <sstream>

#include <sensor_msgs/JointState.h>

#include "frame_ports.h"
#include "imagenets/blocks/robot.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Forward kinematics of a serial chain in the classic Denavit-Hartenberg convention
// (robot_description/robot_model.h). The chain is a robot description's arm or head, so a net
// reads the robot's numbers from its description file instead of copying them, or a DH table
// written in the property `dh_table` for a chain that has no description.
class DhForwardKinematics : public Block {
 public:
  DhForwardKinematics() {
    addInput<sensor_msgs::JointState>("joints", "joint positions (rad); picked by name, or in order for a table");
    addOutput<geometry_msgs::TransformStamped>("frame", "base_frame -> tip_frame (the tip, then tool_offset)");
    addOutput<geometry_msgs::PoseArray>("links", "every link frame 1..n in base_frame (rviz shows it as arrows)");
    addProperty<std::string>("chain", "table",
                             "the kinematic chain: the description's `arm` or `head`, or the property `dh_table`")
        .choices({"table", "arm", "head"});
    addProperty<std::string>("description", "", "robot description YAML (required)").path();
    addProperty<std::string>("tip", "last_link",
                             "end of the chain: its last link, or a frame of the description (tcp, marker, "
                             "hand_camera on the arm; left_camera, right_camera on the head)")
        .choices({"last_link", "tcp", "marker", "hand_camera", "left_camera", "right_camera"});
    addProperty<std::string>("from", "base",
                             "start of the chain: the robot base (with the chain's mount) or the chain's link 0")
        .choices({"base", "link_0"});
    addProperty<std::vector<double>>("dh_table", std::vector<double>{},
                                     "with chain `table`: classic DH rows, 4 values per joint: d (m), theta offset "
                                     "(rad), a (m), alpha (rad)");
    addProperty<std::string>("joint_names", "",
                             "comma-separated joint names; empty: the description's, or for a table the first n "
                             "positions in order");
    addProperty<std::vector<double>>("tool_offset", std::vector<double>{0, 0, 0, 0, 0, 0},
                                     "tip -> output frame: x y z (m) roll pitch yaw (rad, fixed axes x-y-z)");
    addProperty<std::string>("base_frame", "base_link", "frame_id of the outputs");
    addProperty<std::string>("tip_frame", "tool", "child_frame_id of `frame`");
  }

  void process(Context& ctx) override {
    const std::string chain_name = ctx.property<std::string>("chain");
    robot_description::KinematicChain chain;
    Eigen::Isometry3d tip = Eigen::Isometry3d::Identity();
    if (chain_name == "table") {
      try {
        chain.joints = robot_description::parseDhTable(ctx.property<std::vector<double>>("dh_table"));
      } catch (const std::invalid_argument& e) {
        throw BlockError(std::string("property 'dh_table': ") + e.what());
      }
      chain.link_prefix = "link_";
      if (ctx.property<std::string>("tip") != "last_link") {
        throw BlockError("property 'tip': '" + ctx.property<std::string>("tip") +
                         "' needs a robot description (chain arm or head), not a DH table");
      }
    } else {
      const auto& d = robotDescription(ctx.property<std::string>("description"));
      chain = chain_name == "arm" ? d.arm : d.head;
      tip = tipOf(d, chain_name, ctx.property<std::string>("tip"));
    }
    if (ctx.property<std::string>("from") == "link_0") chain.mount = Eigen::Isometry3d::Identity();

    const auto offset = ctx.property<std::vector<double>>("tool_offset");
    if (offset.size() != 6) {
      throw BlockError("property 'tool_offset': " + std::to_string(offset.size()) + " values, expected 6");
    }
    auto joints = ctx.input<sensor_msgs::JointState>("joints");
    const std::vector<double> q = select(*joints, ctx.property<std::string>("joint_names"), chain, chain_name);

    std::vector<Eigen::Isometry3d> links;
    try {
      links = chain.linkFrames(q);
    } catch (const std::invalid_argument& e) {
      throw BlockError(std::string("input 'joints': ") + e.what());
    }
    Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();
    tool.translation() = Eigen::Vector3d(offset[0], offset[1], offset[2]);
    tool.linear() = (Eigen::AngleAxisd(offset[5], Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(offset[4], Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(offset[3], Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();

    std_msgs::Header header = joints->header;
    header.frame_id = ctx.property<std::string>("base_frame");
    ctx.output("frame", frameMsg(links.back() * tip * tool, header, ctx.property<std::string>("tip_frame")));
    geometry_msgs::PoseArray::Ptr poses(new geometry_msgs::PoseArray);
    poses->header = header;
    for (size_t i = 1; i < links.size(); ++i) poses->poses.push_back(frames::toPose(links[i]));
    ctx.output("links", poses);
  }

 private:
  // Last link -> the named tip frame of the description.
  static Eigen::Isometry3d tipOf(const robot_description::RobotDescription& d, const std::string& chain,
                                 const std::string& tip) {
    if (tip == "last_link") return Eigen::Isometry3d::Identity();
    const bool arm_tip = tip == "tcp" || tip == "marker" || tip == "hand_camera";
    if (arm_tip != (chain == "arm")) {
      throw BlockError("property 'tip': '" + tip + "' is not on the " + chain + " chain");
    }
    if (tip == "tcp") return d.tool.pose;
    if (tip == "marker") return d.tool.pose * d.marker.pose;
    if (tip == "hand_camera") return d.tool.pose * d.hand_camera.pose;
    const robot_description::RobotModel model(d);
    return tip == "left_camera" ? d.left_camera.pose : d.left_camera.pose * model.leftToRight();
  }

  static std::vector<double> select(const sensor_msgs::JointState& js, const std::string& names_text,
                                    const robot_description::KinematicChain& chain, const std::string& chain_name) {
    std::vector<std::string> names;
    std::stringstream list(names_text);
    std::string name;
    while (std::getline(list, name, ',')) {
      name.erase(0, name.find_first_not_of(" \t"));
      name.erase(name.find_last_not_of(" \t") + 1);
      if (!name.empty()) names.push_back(name);
    }
    if (names.empty() && chain_name != "table") names = chain.names();
    if (names.empty()) {
      const size_t n = chain.joints.size();
      if (js.position.size() < n) {
        throw BlockError("input 'joints': " + std::to_string(js.position.size()) + " positions, the DH table has " +
                         std::to_string(n) + " joints");
      }
      return std::vector<double>(js.position.begin(), js.position.begin() + n);
    }
    if (names.size() != chain.joints.size()) {
      throw BlockError("property 'joint_names': " + std::to_string(names.size()) + " names for a chain of " +
                       std::to_string(chain.joints.size()) + " joints");
    }
    return jointPositions(js, names, "joints");
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::DhForwardKinematics, "imagenets/DhForwardKinematics", "frames",
                         "Forward kinematics of a robot description's arm or head, or of a DH table");
