#include "imagenets/net.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <boost/filesystem.hpp>
#include <yaml-cpp/yaml.h>

#include "imagenets/net_builder.h"

namespace imagenets {

namespace {
thread_local const NetSpec* current_spec = nullptr;
}

const NetSpec* LoadContext::current() { return current_spec; }
LoadContext::Scope::Scope(const NetSpec& spec) : previous_(current_spec) { current_spec = &spec; }
LoadContext::Scope::~Scope() { current_spec = previous_; }

std::string FeedbackInitial::str() const {
  if (fromPort()) return block + "." + port;
  std::ostringstream os;
  os.precision(12);
  os << value;
  return os.str();
}

std::string SourceLocation::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line);
}

namespace {
std::string joinLines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}
}  // namespace

NetError::NetError(std::vector<std::string> errors) : std::runtime_error(joinLines(errors)), errors_(std::move(errors)) {}

// ---------------------------------------------------------------------------------------------
// Parsing

namespace {

struct Parser {
  std::string origin;
  std::vector<std::string> errors;

  SourceLocation at(const YAML::Node& node) const {
    return SourceLocation{origin, node.Mark().is_null() ? 0 : node.Mark().line + 1};
  }
  void error(const YAML::Node& node, const std::string& what) { errors.push_back(at(node).str() + ": " + what); }

  static std::string text(const YAML::Node& node) {
    if (node.IsScalar()) return node.Scalar();
    YAML::Emitter out;
    out << YAML::Flow << node;
    return out.c_str();
  }

  bool splitEndpoint(const YAML::Node& node, const std::string& s, std::string& block, std::string& port) {
    auto dot = s.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == s.size() || s.find('.', dot + 1) != std::string::npos) {
      error(node, "'" + s + "' is not of the form block.port");
      return false;
    }
    block = s.substr(0, dot);
    port = s.substr(dot + 1);
    return true;
  }

  static std::string trim(const std::string& s) {
    auto b = s.find_first_not_of(" \t");
    auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  }

  void parseLink(const YAML::Node& item, NetSpec& spec) {
    std::string from, to;
    if (item.IsScalar()) {
      const std::string& s = item.Scalar();
      auto arrow = s.find("->");
      if (arrow == std::string::npos) {
        error(item, "link '" + s + "' is not of the form 'block.port -> block.port'");
        return;
      }
      from = trim(s.substr(0, arrow));
      to = trim(s.substr(arrow + 2));
    } else if (item.IsMap() && item["from"] && item["to"]) {
      from = item["from"].as<std::string>();
      to = item["to"].as<std::string>();
    } else {
      error(item, "a link is 'block.port -> block.port' or {from: block.port, to: block.port}");
      return;
    }
    LinkSpec link;
    link.loc = at(item);
    if (splitEndpoint(item, from, link.from_block, link.from_port) &&
        splitEndpoint(item, to, link.to_block, link.to_port)) {
      spec.links.push_back(link);
    }
  }

  // One number of a `feedback:` key; on a bad value an error naming key and value, and nullopt.
  std::optional<double> feedbackNumber(const YAML::Node& node, const std::string& where, const std::string& key) {
    const YAML::Node v = node[key];
    double d = 0;
    if (!v.IsScalar() || !YAML::convert<double>::decode(v, d) || !std::isfinite(d)) {
      error(v, where + key + " '" + text(v) + "' is not a number");
      return std::nullopt;
    }
    return d;
  }

  // `initial`: a number, block.port, or a list of them.
  void parseInitial(const YAML::Node& node, const std::string& where, FeedbackSpec& f) {
    std::vector<YAML::Node> items;
    if (node.IsSequence()) {
      for (const auto& item : node) items.push_back(item);
    } else {
      items.push_back(node);
    }
    if (items.empty()) error(node, where + "'initial' is empty");
    for (const YAML::Node& item : items) {
      FeedbackInitial init;
      if (!item.IsScalar()) {
        error(item, where + "initial '" + text(item) + "' is neither a number nor block.port");
        continue;
      }
      if (YAML::convert<double>::decode(item, init.value)) {
        if (!std::isfinite(init.value)) {
          error(item, where + "initial '" + item.Scalar() + "' is not a finite number");
          continue;
        }
      } else {
        const std::string s = item.Scalar();
        auto dot = s.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == s.size() || s.find('.', dot + 1) != std::string::npos) {
          error(item, where + "initial '" + s + "' is neither a number nor block.port");
          continue;
        }
        init.block = s.substr(0, dot);
        init.port = s.substr(dot + 1);
      }
      f.initial.push_back(init);
    }
  }

  void parseFeedback(const std::string& block, const YAML::Node& node, BlockSpec& b) {
    const std::string where = "block '" + block + "': feedback: ";
    if (!node.IsMap()) {
      error(node, where + "expected a map with property, from/to/step (or values), score, goal");
      return;
    }
    static const std::set<std::string> known{"property", "from",    "to",          "step",        "values",
                                             "score",    "goal",    "search",      "parallel",    "initial",
                                             "good_enough", "coarse_step", "fine_radius"};
    for (const auto& kv : node) {
      if (!known.count(kv.first.Scalar())) error(kv.first, where + "unknown key '" + kv.first.Scalar() + "'");
    }
    const size_t errors_before = errors.size();
    FeedbackSpec f;
    f.loc = at(node);
    try {
      if (!node["property"]) return error(node, where + "missing 'property'");
      f.property = node["property"].as<std::string>();
      if (!node["score"]) return error(node, where + "missing 'score' (block.port of a std_msgs/Float64)");
      std::string score = node["score"].as<std::string>();
      if (!splitEndpoint(node["score"], score, f.score_block, f.score_port)) return;
      std::string goal = node["goal"] ? node["goal"].as<std::string>() : "maximize";
      if (goal != "maximize" && goal != "minimize") {
        return error(node["goal"], where + "goal '" + goal + "' is neither maximize nor minimize");
      }
      f.maximize = goal == "maximize";
      f.search = node["search"] ? node["search"].as<std::string>() : "exhaustive";
      if (f.search != "exhaustive" && f.search != "coarse_to_fine") {
        return error(node["search"], where + "search '" + f.search + "' is neither exhaustive nor coarse_to_fine");
      }
      if (node["parallel"] && (!node["parallel"].IsScalar() || !YAML::convert<bool>::decode(node["parallel"], f.parallel))) {
        return error(node["parallel"], where + "parallel '" + text(node["parallel"]) + "' is neither true nor false");
      }
      if (node["values"]) {
        if (node["from"] || node["to"] || node["step"]) {
          return error(node, where + "give either 'values' or 'from/to/step', not both");
        }
        f.values = node["values"].as<std::vector<double>>();
        if (f.values.empty()) return error(node["values"], where + "'values' is empty");
      } else {
        if (!node["from"] || !node["to"]) return error(node, where + "missing 'from'/'to' (or 'values')");
        f.from = feedbackNumber(node, where, "from");
        f.to = feedbackNumber(node, where, "to");
        f.step = node["step"] ? feedbackNumber(node, where, "step") : std::optional<double>(1.0);
        if (!f.from || !f.to || !f.step) return;
        if (!(*f.step > 0)) return error(node["step"] ? node["step"] : node, where + "step " + text(node["step"]) + " must be > 0");
        // A range runs from `from` towards `to`, downwards when `to` is below `from` (the candidates
        // most likely to succeed first). Count steps with a tolerance so 40..80 step 0.1 ends at 80.
        const double direction = *f.to < *f.from ? -1.0 : 1.0;
        size_t n = static_cast<size_t>(std::floor(std::abs(*f.to - *f.from) / *f.step + 1e-9)) + 1;
        for (size_t i = 0; i < n; ++i) f.values.push_back(*f.from + direction * *f.step * static_cast<double>(i));
      }
      if (node["initial"]) parseInitial(node["initial"], where, f);
      if (node["good_enough"]) f.good_enough = feedbackNumber(node, where, "good_enough");
      if (node["coarse_step"] || node["fine_radius"]) {
        const YAML::Node key = node["coarse_step"] ? node["coarse_step"] : node["fine_radius"];
        if (f.search != "coarse_to_fine") {
          return error(key, where + "coarse_step and fine_radius need search: coarse_to_fine (search is " + f.search + ")");
        }
        if (!f.from) return error(key, where + "coarse_step and fine_radius need from/to/step, not 'values'");
        if (!node["coarse_step"] || !node["fine_radius"]) {
          return error(key, where + "give both coarse_step and fine_radius (only " +
                                (node["coarse_step"] ? "coarse_step" : "fine_radius") + " is given)");
        }
        f.coarse_step = feedbackNumber(node, where, "coarse_step");
        f.fine_radius = feedbackNumber(node, where, "fine_radius");
        if (f.coarse_step && !(*f.coarse_step > 0)) {
          error(node["coarse_step"], where + "coarse_step " + text(node["coarse_step"]) + " must be > 0");
        }
        if (f.fine_radius && *f.fine_radius < 0) {
          error(node["fine_radius"], where + "fine_radius " + text(node["fine_radius"]) + " must be >= 0");
        }
      }
    } catch (const YAML::Exception& e) {
      return error(node, where + "bad value: " + e.msg);
    }
    if (errors.size() == errors_before) b.feedback = f;
  }

  void parseBlock(const YAML::Node& key, const YAML::Node& body, NetSpec& spec) {
    BlockSpec b;
    b.name = key.Scalar();
    b.loc = at(key);
    if (!body.IsMap()) return error(key, "block '" + b.name + "': expected a map with 'type'");
    static const std::set<std::string> known{"type", "properties", "feedback", "doc"};
    for (const auto& kv : body) {
      if (!known.count(kv.first.Scalar())) {
        error(kv.first, "block '" + b.name + "': unknown key '" + kv.first.Scalar() +
                            "' (expected type, properties, feedback, doc)");
      }
    }
    if (!body["type"] || !body["type"].IsScalar()) return error(key, "block '" + b.name + "': missing 'type'");
    b.type = body["type"].Scalar();
    if (const YAML::Node props = body["properties"]) {
      if (!props.IsMap()) {
        error(props, "block '" + b.name + "': 'properties' must be a map");
      } else {
        for (const auto& kv : props) b.properties.push_back(PropertySetting{kv.first.Scalar(), text(kv.second), at(kv.first)});
      }
    }
    if (const YAML::Node fb = body["feedback"]) parseFeedback(b.name, fb, b);
    spec.blocks.push_back(std::move(b));
  }
};

}  // namespace

NetSpec parseNetText(const std::string& yaml, const std::string& origin, const std::string& base_dir) {
  Parser p{origin, {}};
  NetSpec spec;
  spec.origin = origin;
  spec.base_dir = base_dir;
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw NetError({origin + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                    ": malformed YAML: " + e.msg});
  }
  if (!root.IsMap()) throw NetError({origin + ": a net is a YAML map with 'blocks' and 'links'"});
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    // `designer:` holds what an editor keeps beside the net (block positions); the engine ignores it.
    if (key != "blocks" && key != "links" && key != "doc" && key != "designer") {
      p.error(kv.first, "unknown key '" + key + "' (a net has blocks, links, doc and designer)");
    }
  }
  const YAML::Node blocks = root["blocks"];
  if (!blocks || !blocks.IsMap() || blocks.size() == 0) {
    throw NetError({origin + ": 'blocks' must be a non-empty map of block name to {type, properties}"});
  }
  for (const auto& kv : blocks) p.parseBlock(kv.first, kv.second, spec);
  if (const YAML::Node links = root["links"]) {
    if (!links.IsSequence()) p.error(links, "'links' must be a list of 'block.port -> block.port'");
    else for (const auto& item : links) p.parseLink(item, spec);
  }
  if (!p.errors.empty()) throw NetError(p.errors);
  return spec;
}

NetSpec parseNetFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw NetError({path + ": cannot read net file: " + std::strerror(errno)});
  std::stringstream ss;
  ss << in.rdbuf();
  std::string dir = boost::filesystem::absolute(path).parent_path().string();
  return parseNetText(ss.str(), path, dir);
}

// ---------------------------------------------------------------------------------------------
// Building

int Net::findNode(const std::string& name) const {
  for (size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::unique_ptr<Net> Net::build(const NetSpec& spec) {
  NetBuilder builder(spec);
  builder.createBlocks();
  builder.linkBlocks();
  builder.linkFeedbackInitials();
  builder.orderBlocks();
  builder.checkFeedback();
  return builder.finish();
}

std::unique_ptr<Net> Net::loadFile(const std::string& path) { return build(parseNetFile(path)); }

Endpoint Net::resolveOutput(const std::string& block_port) const {
  auto dot = block_port.find('.');
  int n = findNode(block_port.substr(0, dot));
  if (dot == std::string::npos || n < 0) throw NetError({origin_ + ": no block for output '" + block_port + "'"});
  int p = nodes_[n].block->outputIndex(block_port.substr(dot + 1));
  if (p < 0) {
    throw NetError({origin_ + ": block '" + nodes_[n].name + "' has no output port '" + block_port.substr(dot + 1) +
                    "' (outputs: " + portList(nodes_[n].block->outputs()) + ")"});
  }
  return Endpoint{n, p};
}

Endpoint Net::resolveInput(const std::string& block_port) const {
  auto dot = block_port.find('.');
  int n = findNode(block_port.substr(0, dot));
  if (dot == std::string::npos || n < 0) throw NetError({origin_ + ": no block for input '" + block_port + "'"});
  int p = nodes_[n].block->inputIndex(block_port.substr(dot + 1));
  if (p < 0) {
    throw NetError({origin_ + ": block '" + nodes_[n].name + "' has no input port '" + block_port.substr(dot + 1) +
                    "' (inputs: " + portList(nodes_[n].block->inputs()) + ")"});
  }
  return Endpoint{n, p};
}

std::vector<int> Net::descendants(int from) const {
  std::vector<bool> seen(nodes_.size(), false);
  std::vector<int> stack{from}, out;
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    for (int d : nodes_[n].downstream) {
      if (!seen[d]) {
        seen[d] = true;
        out.push_back(d);
        stack.push_back(d);
      }
    }
  }
  return out;
}

}  // namespace imagenets
