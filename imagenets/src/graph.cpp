#include "imagenets/graph.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include <boost/filesystem.hpp>

#include "imagenets/registry.h"
#include "imagenets/xml_escape.h"

namespace imagenets {

std::string typeColor(const std::string& type_name) {
  // Well-known types get fixed, distinct colours; others a hue from their name.
  static const std::map<std::string, std::string> fixed{
      {"sensor_msgs/Image", "#4e79a7"},       {"sensor_msgs/CameraInfo", "#f28e2b"},
      {"geometry_msgs/TransformStamped", "#e15759"}, {"geometry_msgs/PoseArray", "#b07aa1"},
      {"std_msgs/Float64", "#59a14f"},        {"sensor_msgs/JointState", "#edc948"},
      {"sensor_msgs/PointCloud2", "#76b7b2"}, {"imagenets/FeedbackTrace", "#ff9da7"}};
  auto it = fixed.find(type_name);
  if (it != fixed.end()) return it->second;
  // HSV (hue from the name, s=0.45, v=0.9) to #rrggbb.
  const double h = static_cast<double>(std::hash<std::string>{}(type_name) % 360) / 60.0;
  const double v = 0.9, c = v * 0.45, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  double rgb[3][6] = {{c, x, 0, 0, x, c}, {x, c, c, x, 0, 0}, {0, 0, x, c, c, x}};
  const int sector = static_cast<int>(h) % 6;
  char out[8];
  std::snprintf(out, sizeof out, "#%02x%02x%02x", static_cast<int>((rgb[0][sector] + m) * 255),
                static_cast<int>((rgb[1][sector] + m) * 255), static_cast<int>((rgb[2][sector] + m) * 255));
  return out;
}


namespace {

// Paths are stored resolved (absolute); the picture shows them as a net file would write them:
// relative to the net file's folder when near it (at most two levels up), so no machine's
// checkout path shows.
std::string relativeToNet(const std::string& path, const std::string& base_dir) {
  namespace fs = boost::filesystem;
  if (path.empty() || path[0] != '/' || base_dir.empty()) return path;
  const fs::path relative = fs::path(path).lexically_normal().lexically_relative(fs::absolute(base_dir).lexically_normal());
  int up = 0;
  for (const auto& part : relative) up += part == "..";
  if (relative.empty() || up > 2) return path;
  return relative.string();
}

// Draws the blocks and links of `net`; node ids get `prefix` so nested nets do not clash.
void drawNet(std::ostream& os, const Net& net, const std::string& prefix, bool expand, std::set<std::string>& types,
             const std::string& indent) {
  for (size_t i = 0; i < net.nodes().size(); ++i) {
    const Net::Node& n = net.node(i);
    const Block& b = *n.block;
    const std::string id = prefix + "b" + std::to_string(i);
    const std::string type = b.info() ? b.info()->type : "?";
    os << indent << id << " [label=<<table border=\"1\" cellborder=\"0\" cellspacing=\"1\" bgcolor=\"#f7f7f7\">";
    os << "<tr><td colspan=\"2\"><b>" << xmlEscape(n.name) << "</b></td></tr>";
    os << "<tr><td colspan=\"2\"><font point-size=\"9\">" << xmlEscape(type) << "</font></td></tr>";
    const size_t rows = std::max(b.inputs().size(), b.outputs().size());
    for (size_t r = 0; r < rows; ++r) {
      os << "<tr>";
      if (r < b.inputs().size()) {
        const PortSpec& p = b.inputs()[r];
        types.insert(p.type->name);
        os << "<td port=\"i_" << xmlEscape(p.name) << "\" align=\"left\" bgcolor=\"" << typeColor(p.type->name) << "\">"
           << xmlEscape(p.name) << "</td>";
      } else {
        os << "<td></td>";
      }
      if (r < b.outputs().size()) {
        const PortSpec& p = b.outputs()[r];
        types.insert(p.type->name);
        os << "<td port=\"o_" << xmlEscape(p.name) << "\" align=\"right\" bgcolor=\"" << typeColor(p.type->name) << "\">"
           << xmlEscape(p.name) << "</td>";
      } else {
        os << "<td></td>";
      }
      os << "</tr>";
    }
    for (const auto& spec : b.propertySpecs()) {
      const PropertyValue v = b.propertyValue(spec.name());
      if (v == spec.defaultValue()) continue;
      std::string text = toString(v);
      if (spec.isPath()) text = relativeToNet(text, net.baseDir());
      if (text.size() > 48) text = "..." + text.substr(text.size() - 45);
      os << "<tr><td colspan=\"2\" align=\"left\"><font point-size=\"8\">" << xmlEscape(spec.name()) << " = "
         << xmlEscape(text) << "</font></td></tr>";
    }
    os << "</table>>];\n";
    if (expand && b.subNet()) {
      const Net& inner = *b.subNet();
      const std::string inner_prefix = id + "_";
      os << indent << "subgraph cluster_" << id << " {\n"
         << indent << "  label=\"" << xmlEscape(n.name) << ": " << xmlEscape(relativeToNet(inner.origin(), net.baseDir())) << "\"; style=rounded; "
         << "color=\"#888888\";\n";
      drawNet(os, inner, inner_prefix, expand, types, indent + "  ");
      os << indent << "}\n";
      if (!inner.nodes().empty()) {
        os << indent << id << " -> " << inner_prefix << "b0 [lhead=cluster_" << id
           << ", style=dotted, arrowhead=none, color=\"#888888\"];\n";
      }
    }
  }
  for (size_t i = 0; i < net.nodes().size(); ++i) {
    const Net::Node& n = net.node(i);
    const std::string id = prefix + "b" + std::to_string(i);
    for (size_t p = 0; p < n.input_links.size(); ++p) {
      const Endpoint& l = n.input_links[p];
      if (!l.valid()) continue;
      const PortSpec& out = net.node(l.node).block->outputs()[l.port];
      os << indent << prefix << "b" << l.node << ":o_" << out.name << ":e -> " << id << ":i_"
         << n.block->inputs()[p].name << ":w [color=\"" << typeColor(out.type->name) << "\", penwidth=2];\n";
    }
    if (n.feedback) {
      const int score = net.findNode(n.feedback->score_block);
      os << indent << prefix << "b" << score << ":o_" << n.feedback->score_port << " -> " << id
         << " [style=dashed, color=\"#555555\", constraint=false, label=\"feedback: " << xmlEscape(n.feedback->property)
         << " (" << (n.feedback->maximize ? "max" : "min") << ")\"];\n";
      for (const FeedbackInitial& init : n.feedback->initial) {
        if (!init.fromPort()) continue;
        os << indent << prefix << "b" << net.findNode(init.block) << ":o_" << init.port << ":e -> " << id
           << " [style=dotted, color=\"#555555\", label=\"initial " << xmlEscape(n.feedback->property) << "\"];\n";
      }
    }
  }
}

}  // namespace

std::string toDot(const Net& net, bool expand_sub_nets) {
  std::ostringstream os;
  std::set<std::string> types;
  os << "digraph imagenet {\n  rankdir=LR; compound=true;\n  node [shape=plaintext, fontname=\"Helvetica\"];\n"
     << "  edge [fontname=\"Helvetica\", fontsize=9];\n";
  os << "  label=\"" << xmlEscape(net.origin()) << "\"; labelloc=t;\n";
  drawNet(os, net, "", expand_sub_nets, types, "  ");
  // Legend: one swatch per data type used.
  os << "  legend [label=<<table border=\"0\" cellspacing=\"2\"><tr><td><b>data types</b></td></tr>";
  for (const auto& t : types) {
    os << "<tr><td bgcolor=\"" << typeColor(t) << "\">" << xmlEscape(t) << "</td></tr>";
  }
  os << "</table>>];\n}\n";
  return os.str();
}

}  // namespace imagenets
