#include <visualization_msgs/Marker.h>

#include "frame_ports.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// An object model for the 3D scene (paper 3.6, the Joiner's objects): a box, sphere, cylinder or
// a mesh given by URL (package://pkg/path.stl|.dae, file:///path), placed by an input frame or by
// its properties. Output is an rviz marker; the Joiner3D collects them.
class ObjectModel : public Block {
 public:
  ObjectModel() {
    addOptionalInput<geometry_msgs::TransformStamped>("pose", "where the object is (parent -> object); absent: `frame_id` + `offset`");
    addOutput<visualization_msgs::Marker>("marker", "the object as an rviz marker");
    addProperty<std::string>("name", "object", "object name (marker namespace)");
    addProperty<std::string>("shape", "box", "model").choices({"box", "sphere", "cylinder", "mesh"});
    addProperty<std::vector<double>>("size", std::vector<double>{0.1, 0.1, 0.1},
                                     "x, y, z extent (m); for a mesh: scale factors");
    addProperty<std::string>("mesh_url", "", "mesh resource for shape 'mesh' (package:// or file:// URL)");
    addProperty<std::vector<double>>("colour", std::vector<double>{0.8, 0.8, 0.8, 1.0}, "r, g, b, a (0..1)");
    addProperty<std::string>("frame_id", "base_link", "frame the object is given in when `pose` is absent");
    addProperty<std::vector<double>>("offset", std::vector<double>{0, 0, 0, 0, 0, 0},
                                     "pose in frame_id (or after `pose`): x y z (m) roll pitch yaw (rad)");
  }

  void process(Context& ctx) override {
    const auto size = ctx.property<std::vector<double>>("size");
    const auto colour = ctx.property<std::vector<double>>("colour");
    const auto offset = ctx.property<std::vector<double>>("offset");
    if (size.size() != 3) throw BlockError("property 'size': " + std::to_string(size.size()) + " values, expected 3");
    if (colour.size() != 4) throw BlockError("property 'colour': " + std::to_string(colour.size()) + " values, expected 4");
    if (offset.size() != 6) throw BlockError("property 'offset': " + std::to_string(offset.size()) + " values, expected 6");
    for (double s : size) {
      if (!(s > 0)) throw BlockError("property 'size': extents must be positive");
    }
    const std::string shape = ctx.property<std::string>("shape");
    const std::string url = ctx.property<std::string>("mesh_url");
    if (shape == "mesh" && url.rfind("package://", 0) != 0 && url.rfind("file://", 0) != 0) {
      throw BlockError("property 'mesh_url': '" + url + "' is not a package:// or file:// URL");
    }
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.translation() = Eigen::Vector3d(offset[0], offset[1], offset[2]);
    local.linear() = (Eigen::AngleAxisd(offset[5], Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(offset[4], Eigen::Vector3d::UnitY()) *
                      Eigen::AngleAxisd(offset[3], Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
    visualization_msgs::Marker::Ptr m(new visualization_msgs::Marker);
    if (ctx.hasInput("pose")) {
      geometry_msgs::TransformStamped::ConstPtr pose_msg;
      const Eigen::Isometry3d pose = inputFrame(ctx, "pose", &pose_msg);
      m->header = pose_msg->header;
      m->pose = frames::toPose(pose * local);
    } else {
      m->header.frame_id = ctx.property<std::string>("frame_id");
      m->pose = frames::toPose(local);
    }
    m->ns = ctx.property<std::string>("name");
    m->action = visualization_msgs::Marker::ADD;
    m->type = shape == "box" ? visualization_msgs::Marker::CUBE
              : shape == "sphere" ? visualization_msgs::Marker::SPHERE
              : shape == "cylinder" ? visualization_msgs::Marker::CYLINDER
                                    : visualization_msgs::Marker::MESH_RESOURCE;
    if (shape == "mesh") {
      m->mesh_resource = url;
      m->mesh_use_embedded_materials = true;
    }
    m->scale.x = size[0];
    m->scale.y = size[1];
    m->scale.z = size[2];
    m->color.r = colour[0];
    m->color.g = colour[1];
    m->color.b = colour[2];
    m->color.a = colour[3];
    m->frame_locked = true;
    ctx.output("marker", m);
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::ObjectModel, "imagenets/ObjectModel", "visualization",
                         "An object model (box, sphere, cylinder, mesh URL) for the 3D scene");
