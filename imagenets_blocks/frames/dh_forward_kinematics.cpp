#include <algorithm>
#include <sstream>

#include <sensor_msgs/JointState.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// Forward kinematics of a serial arm from its classic Denavit-Hartenberg table (convention in
// imagenets/blocks/frames.h: A_i = Rot_z(theta_i + q_i) Trans_z(d_i) Trans_x(a_i) Rot_x(alpha_i)).
class DhForwardKinematics : public Block {
 public:
  DhForwardKinematics() {
    addInput<sensor_msgs::JointState>("joints", "joint positions (rad); picked by `joint_names` or in order");
    addOutput<geometry_msgs::TransformStamped>("frame", "base_frame -> tip_frame (last link, then tool_offset)");
    addOutput<geometry_msgs::PoseArray>("links", "every link frame 1..n in base_frame (rviz shows it as arrows)");
    addProperty<std::vector<double>>("dh_table", std::vector<double>{},
                                     "classic DH rows, 4 values per joint: d (m), theta offset (rad), a (m), "
                                     "alpha (rad)");
    addProperty<std::string>("joint_names", "",
                             "comma-separated joint names, one per DH row; empty: the first n positions in order");
    addProperty<std::vector<double>>("tool_offset", std::vector<double>{0, 0, 0, 0, 0, 0},
                                     "last link -> tip: x y z (m) roll pitch yaw (rad, fixed axes x-y-z)");
    addProperty<std::string>("base_frame", "base_link", "frame_id of the outputs");
    addProperty<std::string>("tip_frame", "tool", "child_frame_id of `frame`");
  }

  void process(Context& ctx) override {
    std::vector<frames::DhRow> table;
    try {
      table = frames::parseDhTable(ctx.property<std::vector<double>>("dh_table"));
    } catch (const frames::FrameError& e) {
      throw BlockError(std::string("property 'dh_table': ") + e.what());
    }
    const auto offset = ctx.property<std::vector<double>>("tool_offset");
    if (offset.size() != 6) {
      throw BlockError("property 'tool_offset': " + std::to_string(offset.size()) + " values, expected 6");
    }
    auto joints = ctx.input<sensor_msgs::JointState>("joints");
    if (!joints) throw BlockError("input 'joints': no joint state");
    const std::vector<double> q = select(*joints, ctx.property<std::string>("joint_names"), table.size());

    std::vector<Eigen::Isometry3d> chain;
    try {
      chain = frames::forwardKinematicsChain(table, q);
    } catch (const frames::FrameError& e) {
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
    ctx.output("frame", frameMsg(chain.back() * tool, header, ctx.property<std::string>("tip_frame")));
    geometry_msgs::PoseArray::Ptr links(new geometry_msgs::PoseArray);
    links->header = header;
    for (const auto& t : chain) links->poses.push_back(frames::toPose(t));
    ctx.output("links", links);
  }

 private:
  static std::vector<double> select(const sensor_msgs::JointState& js, const std::string& names, size_t n) {
    std::vector<double> q;
    if (names.empty()) {
      if (js.position.size() < n) {
        throw BlockError("input 'joints': " + std::to_string(js.position.size()) + " positions, the DH table has " +
                         std::to_string(n) + " joints");
      }
      return std::vector<double>(js.position.begin(), js.position.begin() + n);
    }
    if (js.name.size() != js.position.size()) {
      throw BlockError("input 'joints': " + std::to_string(js.name.size()) + " names but " +
                       std::to_string(js.position.size()) + " positions");
    }
    std::stringstream list(names);
    std::string name;
    while (std::getline(list, name, ',')) {
      name.erase(0, name.find_first_not_of(" \t"));
      name.erase(name.find_last_not_of(" \t") + 1);
      auto it = std::find(js.name.begin(), js.name.end(), name);
      if (it == js.name.end()) throw BlockError("input 'joints': no joint named '" + name + "'");
      q.push_back(js.position[it - js.name.begin()]);
    }
    if (q.size() != n) {
      throw BlockError("property 'joint_names': " + std::to_string(q.size()) + " names for a DH table of " +
                       std::to_string(n) + " joints");
    }
    return q;
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::DhForwardKinematics, "imagenets/DhForwardKinematics", "frames",
                         "Forward kinematics from a classic DH table and joint states");
