#include "imagenets/net_writer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace imagenets {

std::string formatNumber(double value) {
  if (std::isnan(value)) return ".nan";
  if (std::isinf(value)) return value > 0 ? ".inf" : "-.inf";
  char buf[40];
  if (value == std::floor(value) && std::abs(value) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", value);
    return buf;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (std::strtod(buf, nullptr) == value) break;
  }
  return buf;
}

namespace {

// A property's text as written in a net file: a flow sequence or map stays one, anything else is
// a scalar (quoted by the emitter where YAML needs it), so parsing gives the same text back.
YAML::Node propertyNode(const std::string& text) {
  if (!text.empty() && (text.front() == '[' || text.front() == '{')) {
    try {
      return YAML::Load(text);
    } catch (const YAML::Exception&) {
    }
  }
  return YAML::Node(text);
}

YAML::Node feedbackNode(const FeedbackSpec& f) {
  YAML::Node node(YAML::NodeType::Map);
  node["property"] = f.property;
  const auto& v = f.values;
  bool even = v.size() >= 2 && v.back() != v.front();  // ascending or descending
  double step = 0;
  if (even) {
    step = (v.back() - v.front()) / static_cast<double>(v.size() - 1);
    for (size_t i = 0; i < v.size() && even; ++i) {
      const double expected = v.front() + step * static_cast<double>(i);
      even = std::abs(v[i] - expected) <= 1e-9 * std::max(1.0, std::abs(expected));
    }
    // The parser must count the same candidates from from/to/step.
    const double from = std::strtod(formatNumber(v.front()).c_str(), nullptr);
    const double to = std::strtod(formatNumber(v.back()).c_str(), nullptr);
    const double s = std::strtod(formatNumber(step).c_str(), nullptr);
    even = even && static_cast<size_t>(std::floor((to - from) / s + 1e-9)) + 1 == v.size();
  }
  if (even) {
    node["from"] = formatNumber(v.front());
    node["to"] = formatNumber(v.back());
    node["step"] = formatNumber(std::abs(step));
  } else {
    YAML::Node values(YAML::NodeType::Sequence);
    for (double x : v) values.push_back(formatNumber(x));
    node["values"] = values;
  }
  node["score"] = f.score_block + "." + f.score_port;
  node["goal"] = f.maximize ? "maximize" : "minimize";
  node["search"] = f.search;
  node["parallel"] = f.parallel ? "true" : "false";
  if (!f.initial.empty()) {
    YAML::Node initial(YAML::NodeType::Sequence);
    for (const FeedbackInitial& i : f.initial) initial.push_back(i.fromPort() ? i.block + "." + i.port : formatNumber(i.value));
    node["initial"] = f.initial.size() == 1 ? initial[0] : initial;
  }
  if (f.good_enough) node["good_enough"] = formatNumber(*f.good_enough);
  if (f.coarse_step && f.fine_radius) {
    node["coarse_step"] = formatNumber(*f.coarse_step);
    node["fine_radius"] = formatNumber(*f.fine_radius);
  }
  return node;
}

void emitFlow(YAML::Emitter& out, const YAML::Node& node) {
  out << YAML::Flow << node;
}

}  // namespace

std::string writeFeedbackText(const FeedbackSpec& feedback) {
  YAML::Emitter out;
  emitFlow(out, feedbackNode(feedback));
  return out.c_str();
}

std::string writeNetText(const NetSpec& spec, const std::string& previous_text) {
  YAML::Node previous;
  try {
    if (!previous_text.empty()) previous = YAML::Load(previous_text);
  } catch (const YAML::Exception&) {
  }
  // A block missing from the previous text (added since) is an invalid node here, whose IsMap()
  // would throw: test that it exists first.
  auto docOf = [](const YAML::Node& map) -> std::string {
    if (!map.IsDefined() || !map.IsMap()) return "";
    const YAML::Node doc = map["doc"];
    return doc && doc.IsScalar() ? doc.Scalar() : "";
  };
  const YAML::Node previous_blocks = previous.IsMap() ? previous["blocks"] : YAML::Node();

  YAML::Emitter out;
  out << YAML::BeginMap;
  const std::string net_doc = docOf(previous);
  if (!net_doc.empty()) out << YAML::Key << "doc" << YAML::Value << YAML::Literal << net_doc;
  out << YAML::Key << "blocks" << YAML::Value;
  if (spec.blocks.empty()) {
    out << YAML::Flow;
  }
  out << YAML::BeginMap;
  for (const BlockSpec& b : spec.blocks) {
    out << YAML::Key << b.name << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "type" << YAML::Value << b.type;
    const std::string doc =
        previous_blocks && previous_blocks.IsMap() ? docOf(previous_blocks[b.name]) : std::string();
    if (!doc.empty()) out << YAML::Key << "doc" << YAML::Value << doc;
    if (!b.properties.empty()) {
      YAML::Node props(YAML::NodeType::Map);
      for (const PropertySetting& p : b.properties) props[p.name] = propertyNode(p.text);
      out << YAML::Key << "properties" << YAML::Value;
      emitFlow(out, props);
    }
    if (b.feedback) {
      out << YAML::Key << "feedback" << YAML::Value;
      emitFlow(out, feedbackNode(*b.feedback));
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  if (!spec.links.empty()) {
    out << YAML::Key << "links" << YAML::Value << YAML::BeginSeq;
    for (const LinkSpec& l : spec.links) {
      out << (l.from_block + "." + l.from_port + " -> " + l.to_block + "." + l.to_port);
    }
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string setTopLevelSection(const std::string& text, const std::string& key, const std::string& body) {
  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) lines.push_back(line);
  }
  auto startsSection = [](const std::string& line) {
    return !line.empty() && line[0] != ' ' && line[0] != '\t' && line[0] != '#';
  };
  std::vector<std::string> section;
  if (!body.empty()) {
    section.push_back(key + ":");
    std::istringstream in(body);
    std::string line;
    while (std::getline(in, line)) section.push_back(line.empty() ? line : "  " + line);
  }
  size_t begin = lines.size(), end = lines.size();
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (l.compare(0, key.size() + 1, key + ":") == 0) {
      begin = i;
      end = i + 1;
      while (end < lines.size() && !startsSection(lines[end])) ++end;
      // Blank lines and comments just before the next section belong to it.
      while (end > begin + 1 && (lines[end - 1].empty() || lines[end - 1][0] == '#')) --end;
      break;
    }
  }
  if (begin == lines.size()) {
    if (section.empty()) return text;
    while (!lines.empty() && lines.back().empty()) lines.pop_back();
    begin = end = lines.size();
  }
  lines.erase(lines.begin() + static_cast<long>(begin), lines.begin() + static_cast<long>(end));
  lines.insert(lines.begin() + static_cast<long>(begin), section.begin(), section.end());
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

}  // namespace imagenets
