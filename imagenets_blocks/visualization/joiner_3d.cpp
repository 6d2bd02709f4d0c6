#include <map>
#include <set>

#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "frame_ports.h"
#include "imagenets/vision/point_cloud.h"
#include "imagenets/register_block.h"

namespace imagenets {
namespace blocks {

// The paper's Joiner for the 3D view: frames, object models and point clouds combined into one
// scene for rviz. Frames are chained through each other (robot -> camera and camera -> marker
// place the marker in the robot frame), drawn as axis triads with their names; objects and clouds
// are placed the same way. Outputs a MarkerArray (starting with DELETEALL, so stale markers go)
// and the frames as a tf2 message, so rviz can show both from the fixed frame.
class Joiner3D : public Block {
 public:
  Joiner3D() {
    addProperty<int>("frame_inputs", 4, "number of frame inputs frame_1..frame_N").range(0, 32);
    addProperty<int>("object_inputs", 2, "number of object inputs object_1..object_N").range(0, 32);
    addProperty<int>("cloud_inputs", 1, "number of point cloud inputs cloud_1..cloud_N").range(0, 8);
    addProperty<std::string>("fixed_frame", "base_link", "frame of the scene (rviz fixed frame)");
    addProperty<double>("axis_length", 0.1, "length of the drawn frame axes (m)").range(0.001, 100);
    addProperty<double>("point_size", 0.005, "drawn point size (m)").range(0.0001, 1);
    addProperty<int>("max_points", 50000, "points drawn per cloud at most (evenly subsampled)").range(1, 10000000);
    addOutput<visualization_msgs::MarkerArray>("markers", "the scene, in fixed_frame where the frames reach it");
    addOutput<tf2_msgs::TFMessage>("tf", "every input frame as a transform (for a tf2 broadcaster)");
  }

  void configure() override {
    for (int i = 1; i <= property<int>("frame_inputs"); ++i) {
      addOptionalInput<geometry_msgs::TransformStamped>("frame_" + std::to_string(i), "a frame (parent -> child)");
    }
    for (int i = 1; i <= property<int>("object_inputs"); ++i) {
      addOptionalInput<visualization_msgs::Marker>("object_" + std::to_string(i), "an object model (ObjectModel)");
    }
    for (int i = 1; i <= property<int>("cloud_inputs"); ++i) {
      addOptionalInput<sensor_msgs::PointCloud2>("cloud_" + std::to_string(i), "a point cloud (x, y, z, optional rgb)");
    }
  }

  void process(Context& ctx) override {
    tf2_msgs::TFMessage::Ptr tf(new tf2_msgs::TFMessage);
    const Tree tree = frameTree(ctx, tf->transforms);
    visualization_msgs::MarkerArray::Ptr scene(new visualization_msgs::MarkerArray);
    visualization_msgs::Marker clear;
    clear.action = visualization_msgs::Marker::DELETEALL;
    clear.header.frame_id = tree.fixed;
    scene->markers.push_back(clear);
    int id = 0;
    for (const auto& frame : tf->transforms) addFrame(ctx, tree, frame.child_frame_id, id, scene->markers);
    for (const auto& port : inputs()) {
      if (port.name.rfind("object_", 0) == 0 && ctx.hasInput(port.name)) scene->markers.push_back(objectMarker(ctx, tree, port.name, id++));
    }
    for (const auto& port : inputs()) {
      if (port.name.rfind("cloud_", 0) == 0 && ctx.hasInput(port.name)) scene->markers.push_back(cloudMarker(ctx, tree, port.name, id++));
    }
    ctx.output("markers", scene);
    ctx.output("tf", tf);
  }

 private:
  // The input frames: child -> (parent, transform).
  struct Tree {
    std::string fixed;
    std::map<std::string, std::pair<std::string, Eigen::Isometry3d>> parent;

    // Where a frame is in the scene: its pose in fixed_frame if the chain reaches it, else its
    // pose in the root of its chain (rviz then needs TF for that root).
    Eigen::Isometry3d resolve(const std::string& frame, std::string& root) const {
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      std::string f = frame;
      std::set<std::string> seen;
      while (f != fixed && parent.count(f)) {
        if (!seen.insert(f).second) throw BlockError("frames form a cycle through '" + f + "'");
        t = parent.at(f).second * t;
        f = parent.at(f).first;
      }
      root = f;
      return t;
    }
  };

  // The frame inputs, checked, as a tree; each also goes to `transforms` (in input order).
  Tree frameTree(Context& ctx, std::vector<geometry_msgs::TransformStamped>& transforms) const {
    Tree tree;
    tree.fixed = ctx.property<std::string>("fixed_frame");
    for (const auto& port : inputs()) {
      if (port.name.rfind("frame_", 0) != 0 || !ctx.hasInput(port.name)) continue;
      geometry_msgs::TransformStamped::ConstPtr msg;
      const Eigen::Isometry3d t = inputFrame(ctx, port.name, &msg);
      if (msg->child_frame_id.empty() || msg->header.frame_id.empty()) {
        throw BlockError("input '" + port.name + "': frame ids must not be empty");
      }
      if (tree.parent.count(msg->child_frame_id)) {
        throw BlockError("input '" + port.name + "': frame '" + msg->child_frame_id + "' is given twice");
      }
      tree.parent[msg->child_frame_id] = {msg->header.frame_id, t};
      transforms.push_back(*msg);
    }
    return tree;
  }

  // A frame as an axis triad (x red, y green, z blue) with its name above it.
  void addFrame(Context& ctx, const Tree& tree, const std::string& child, int& id,
                std::vector<visualization_msgs::Marker>& markers) const {
    const double axis = ctx.property<double>("axis_length");
    std::string root;
    const Eigen::Isometry3d t = tree.resolve(child, root);
    for (int a = 0; a < 3; ++a) {
      visualization_msgs::Marker m;
      m.header.frame_id = root;
      m.ns = "frames";
      m.id = id++;
      m.type = visualization_msgs::Marker::ARROW;
      m.action = visualization_msgs::Marker::ADD;
      m.pose.orientation.w = 1;
      const Eigen::Vector3d from = t.translation(), to = t * (axis * Eigen::Vector3d::Unit(a));
      m.points = {frames::toPointMsg(from), frames::toPointMsg(to)};
      m.scale.x = axis * 0.08;  // shaft diameter
      m.scale.y = axis * 0.16;  // head diameter
      m.color.r = a == 0;
      m.color.g = a == 1;
      m.color.b = a == 2;
      m.color.a = 1;
      markers.push_back(m);
    }
    visualization_msgs::Marker label;
    label.header.frame_id = root;
    label.ns = "frame_names";
    label.id = id++;
    label.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    label.action = visualization_msgs::Marker::ADD;
    label.pose = frames::toPose(t);
    label.pose.position.z += axis * 0.3;
    label.scale.z = axis * 0.3;
    label.color.r = label.color.g = label.color.b = label.color.a = 1;
    label.text = child;
    markers.push_back(label);
  }

  visualization_msgs::Marker objectMarker(Context& ctx, const Tree& tree, const std::string& port, int id) const {
    auto object = ctx.input<visualization_msgs::Marker>(port);
    Eigen::Isometry3d pose;
    try {
      pose = frames::toIsometry(object->pose, "input '" + port + "' pose");
    } catch (const frames::FrameError& e) {
      throw BlockError(e.what());
    }
    visualization_msgs::Marker m = *object;
    std::string root;
    m.pose = frames::toPose(tree.resolve(object->header.frame_id, root) * pose);
    m.header.frame_id = root;
    m.id = id;
    return m;
  }

  // A cloud as coloured points, evenly subsampled to max_points.
  visualization_msgs::Marker cloudMarker(Context& ctx, const Tree& tree, const std::string& port, int id) const {
    auto cloud_msg = ctx.input<sensor_msgs::PointCloud2>(port);
    std::vector<cloud::PointXYZRGB> points;
    try {
      points = cloud::readPoints(*cloud_msg);
    } catch (const std::invalid_argument& e) {
      throw BlockError("input '" + port + "': " + e.what());
    }
    visualization_msgs::Marker m;
    std::string root;
    m.pose = frames::toPose(tree.resolve(cloud_msg->header.frame_id, root));
    m.header.frame_id = root;
    m.ns = "clouds";
    m.id = id;
    m.type = visualization_msgs::Marker::POINTS;
    m.action = visualization_msgs::Marker::ADD;
    m.scale.x = m.scale.y = ctx.property<double>("point_size");
    m.color.a = 1;
    const size_t max_points = static_cast<size_t>(ctx.property<int>("max_points"));
    const size_t step = std::max<size_t>(1, (points.size() + max_points - 1) / std::max<size_t>(1, max_points));
    for (size_t i = 0; i < points.size(); i += step) {
      geometry_msgs::Point p;
      p.x = points[i].x;
      p.y = points[i].y;
      p.z = points[i].z;
      std_msgs::ColorRGBA c;
      c.r = points[i].r / 255.0f;
      c.g = points[i].g / 255.0f;
      c.b = points[i].b / 255.0f;
      c.a = 1;
      m.points.push_back(p);
      m.colors.push_back(c);
    }
    return m;
  }
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::Joiner3D, "imagenets/Joiner3D", "visualization",
                         "Joins frames, object models and point clouds into one rviz scene (markers + TF)");
