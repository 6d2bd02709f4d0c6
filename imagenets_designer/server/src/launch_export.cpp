#include "launch_export.h"

#include <fstream>
#include <iterator>
#include <sstream>

#include <boost/filesystem.hpp>
#include <ros/package.h>

#include "imagenets/registry.h"
#include "imagenets/xml_escape.h"

namespace imagenets {
namespace designer {

namespace {

// Attribute values may hold a multi-line net (net_yaml): newlines as character references.
std::string xml(const std::string& s) {
  std::string out;
  for (char c : xmlEscape(s)) {
    if (c == '\n') out += "&#10;";
    else out += c;
  }
  return out;
}

// A path inside a ROS package as $(find PACKAGE)/..., so the launch file works anywhere: the
// nearest folder above it with a package.xml, if ROS finds that package there.
std::string launchPath(const std::string& path) {
  namespace fs = boost::filesystem;
  for (fs::path dir = fs::path(path).parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path()) {
    std::ifstream manifest((dir / "package.xml").string());
    if (!manifest) continue;
    const std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
    const size_t begin = text.find("<name>"), end = text.find("</name>");
    if (begin == std::string::npos || end == std::string::npos || end < begin) return path;
    const std::string name = text.substr(begin + 6, end - begin - 6);
    if (ros::package::getPath(name) != dir.string()) return path;
    return "$(find " + name + ")" + path.substr(dir.string().size());
  }
  return path;
}

}  // namespace

std::string exportLaunch(const NetSpec& spec) {
  namespace fs = boost::filesystem;
  std::string group = fs::path(spec.origin).stem().string();
  if (group.empty() || group.find_first_of(" :") != std::string::npos) group = "designer_net";
  for (char& c : group) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  std::ostringstream os;
  os << "<!-- " << xml(spec.origin) << " as nodelets (exported by the ImageNet Designer): every block a nodelet\n"
     << "     in one manager, so images pass by pointer; each link is a remap of an input ~in/<port> to an\n"
     << "     output <block>/out/<port>; properties are private parameters. -->\n";
  os << "<launch>\n  <arg name=\"manager\" default=\"imagenets_manager\"/>\n\n";
  os << "  <group ns=\"" << group << "\">\n";
  os << "    <node pkg=\"nodelet\" type=\"nodelet\" name=\"$(arg manager)\" args=\"manager\" output=\"screen\"/>\n";
  for (const BlockSpec& b : spec.blocks) {
    os << "\n";
    if (b.feedback) {
      os << "    <!-- feedback on '" << xml(b.feedback->property) << "' (score " << xml(b.feedback->score_block) << "."
         << xml(b.feedback->score_port)
         << ") needs the executor: the nodelet keeps the property's value; run the net in an imagenets/SubNet"
            " nodelet to tune it. -->\n";
    }
    os << "    <node pkg=\"nodelet\" type=\"nodelet\" name=\"" << xml(b.name) << "\" args=\"load " << xml(b.type)
       << " $(arg manager)\">\n";
    for (const LinkSpec& l : spec.links) {
      if (l.to_block != b.name) continue;
      os << "      <remap from=\"~in/" << xml(l.to_port) << "\" to=\"" << xml(l.from_block) << "/out/"
         << xml(l.from_port) << "\"/>\n";
    }
    const BlockInfo* info = BlockRegistry::instance().find(b.type);
    const auto block = info ? info->create() : nullptr;
    for (const PropertySetting& p : b.properties) {
      const PropertySpec* ps = block ? block->findProperty(p.name) : nullptr;
      std::string value = p.text;
      PropertyKind kind = ps ? ps->kind() : PropertyKind::String;
      if (ps) {
        try {
          PropertyValue v = ps->parse(p.text, spec.base_dir);
          if (ps->isPath()) v = launchPath(std::get<std::string>(v));
          value = toString(v);
        } catch (const std::exception&) {
        }
      }
      if (kind == PropertyKind::DoubleList) {
        os << "      <rosparam param=\"" << xml(p.name) << "\">" << xml(value) << "</rosparam>\n";
      } else if (kind == PropertyKind::String || kind == PropertyKind::Enum) {
        os << "      <param name=\"" << xml(p.name) << "\" type=\"str\" value=\"" << xml(value) << "\"/>\n";
      } else {
        os << "      <param name=\"" << xml(p.name) << "\" value=\"" << xml(value) << "\"/>\n";
      }
    }
    os << "    </node>\n";
  }
  os << "  </group>\n</launch>\n";
  return os.str();
}

}  // namespace designer
}  // namespace imagenets
