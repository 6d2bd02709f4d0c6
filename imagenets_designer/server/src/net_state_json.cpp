#include "net_state_json.h"

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "imagenets/graph.h"
#include "imagenets/net_writer.h"
#include "imagenets/registry.h"
#include "yaml_json.h"

namespace imagenets {
namespace designer {

std::string jsonText(const nlohmann::json& message) {
  return message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json propertyValueJson(const PropertyValue& value) {
  struct Visitor {
    nlohmann::json operator()(bool b) const { return b; }
    nlohmann::json operator()(int i) const { return i; }
    nlohmann::json operator()(double d) const { return std::isfinite(d) ? nlohmann::json(d) : nlohmann::json(); }
    nlohmann::json operator()(const std::string& s) const { return s; }
    nlohmann::json operator()(const std::vector<double>& v) const { return v; }
  };
  return std::visit(Visitor{}, value);
}

nlohmann::json portJson(const PortSpec& port) {
  return {{"name", port.name}, {"type", port.type->name}, {"doc", port.doc}, {"optional", port.optional}};
}

namespace {

nlohmann::json propertyJson(const PropertySpec& p) {
  std::string kind = kindName(p.kind());
  for (char& c : kind) {
    if (c == ' ') c = '_';
  }
  nlohmann::json out = {{"name", p.name()},
                        {"kind", kind},
                        {"default", propertyValueJson(p.defaultValue())},
                        {"doc", p.doc()},
                        {"path", p.isPath()}};
  if (p.min()) out["min"] = *p.min();
  if (p.max()) out["max"] = *p.max();
  if (!p.allowedChoices().empty()) out["choices"] = p.allowedChoices();
  return out;
}

}  // namespace

nlohmann::json registryJson() {
  nlohmann::json blocks = nlohmann::json::array();
  nlohmann::json types = nlohmann::json::object();
  for (const BlockInfo* info : BlockRegistry::instance().all()) {
    const auto block = info->create();
    nlohmann::json b = {{"type", info->type}, {"category", info->category}, {"doc", info->doc}};
    b["inputs"] = nlohmann::json::array();
    b["outputs"] = nlohmann::json::array();
    b["properties"] = nlohmann::json::array();
    for (const auto& p : block->inputs()) b["inputs"].push_back(portJson(p));
    for (const auto& p : block->outputs()) b["outputs"].push_back(portJson(p));
    for (const auto& p : block->propertySpecs()) b["properties"].push_back(propertyJson(p));
    blocks.push_back(b);
  }
  for (const auto& name : PortType::names()) types[name] = typeColor(name);
  return {{"blocks", blocks}, {"types", types}};
}

nlohmann::json statsJson(const BlockStats& s) {
  return {{"status", statusName(s.status)}, {"message", s.message}, {"runs", s.runs},
          {"last_ms", s.last_ms},          {"mean_ms", s.mean_ms},        {"last_cpu_ms", s.last_cpu_ms},
          {"mean_cpu_ms", s.mean_cpu_ms}};
}

namespace {
// The protocol's names of the event kinds (designer/PROTOCOL.md).
const char* eventKindName(RunEventKind kind) {
  switch (kind) {
    case RunEventKind::BlockStarted: return "started";
    case RunEventKind::BlockFinished: return "finished";
    case RunEventKind::BlockCached: return "cached";
    case RunEventKind::FeedbackTrial: return "trial";
    case RunEventKind::Repetition: return "repetition";
    case RunEventKind::RunFinished: return "run_finished";
  }
  return "?";
}
}  // namespace

nlohmann::json eventJson(const RunEvent& e) {
  nlohmann::json out = {{"op", "event"}, {"kind", eventKindName(e.kind)}, {"block", e.block}};
  switch (e.kind) {
    case RunEventKind::BlockFinished:
    case RunEventKind::BlockCached:
      out["stats"] = statsJson(e.stats);
      break;
    case RunEventKind::FeedbackTrial:
      out["value"] = std::isfinite(e.value) ? nlohmann::json(e.value) : nlohmann::json();
      out["score"] = std::isfinite(e.score) ? nlohmann::json(e.score) : nlohmann::json();
      out["index"] = e.index;
      out["count"] = e.count;
      out["message"] = e.message;
      break;
    case RunEventKind::Repetition:
      out["index"] = e.index;
      out["count"] = e.count;
      out["message"] = e.message;
      break;
    default:
      if (!e.message.empty()) out["message"] = e.message;
  }
  return out;
}

nlohmann::json feedbackJson(const FeedbackSpec& feedback) {
  return yamlToJson(YAML::Load(writeFeedbackText(feedback)));
}

void addPorts(nlohmann::json& block, const Block& instance) {
  block["inputs"] = nlohmann::json::array();
  block["outputs"] = nlohmann::json::array();
  for (const auto& p : instance.inputs()) block["inputs"].push_back(portJson(p));
  for (const auto& p : instance.outputs()) block["outputs"].push_back(portJson(p));
}

nlohmann::json builtNetState(const Net& net, const Executor* executor) {
  nlohmann::json blocks = nlohmann::json::array(), links = nlohmann::json::array();
  for (const auto& node : net.nodes()) {
    nlohmann::json b = {{"name", node.name},
                        {"type", node.block->info() ? node.block->info()->type : "?"},
                        {"position", nullptr},
                        {"has_subnet", node.block->subNet() != nullptr}};
    nlohmann::json props = nlohmann::json::object();
    for (const auto& kv : node.block->propertyValues()) props[kv.first] = toString(kv.second);
    b["properties"] = props;
    b["feedback"] = node.feedback ? feedbackJson(*node.feedback) : nlohmann::json();
    addPorts(b, *node.block);
    b["stats"] = statsJson(executor ? executor->stats(node.name) : BlockStats());
    blocks.push_back(b);
    for (size_t i = 0; i < node.input_links.size(); ++i) {
      const Endpoint& l = node.input_links[i];
      if (!l.valid()) continue;
      const auto& from = net.node(l.node);
      const PortSpec& port = from.block->outputs()[l.port];
      links.push_back({{"from", from.name + "." + port.name},
                       {"to", node.name + "." + node.block->inputs()[i].name},
                       {"type", port.type->name}});
    }
  }
  return {{"op", "net"}, {"file", net.origin()}, {"readonly", true}, {"blocks", blocks}, {"links", links},
          {"errors", nlohmann::json::array()}};
}

void addDocument(nlohmann::json& state, const NetDocument& doc, const Executor& executor) {
  using json = nlohmann::json;
  json blocks = json::array(), links = json::array();
  const Net& net = executor.net();
  for (const BlockSpec& b : doc.spec.blocks) {
    json j = {{"name", b.name}, {"type", b.type}};
    auto pos = doc.positions.find(b.name);
    j["position"] = pos == doc.positions.end() ? json() : json{pos->second[0], pos->second[1]};
    const int n = net.findNode(b.name);
    json props = json::object(), explicit_props = json::array();
    for (const auto& p : b.properties) {
      props[p.name] = p.text;
      explicit_props.push_back(p.name);
    }
    if (n >= 0) {
      const Block& instance = *net.node(n).block;
      for (const auto& spec : instance.propertySpecs()) {
        if (!props.contains(spec.name())) props[spec.name()] = toString(instance.propertyValue(spec.name()));
      }
      addPorts(j, instance);
      j["stats"] = statsJson(executor.stats(b.name));
      j["has_subnet"] = instance.subNet() != nullptr;
    } else {
      j["inputs"] = j["outputs"] = json::array();
      j["stats"] = statsJson(BlockStats());
      j["has_subnet"] = false;
    }
    j["properties"] = props;
    j["explicit"] = explicit_props;
    j["feedback"] = b.feedback ? feedbackJson(*b.feedback) : json();
    blocks.push_back(j);
  }
  for (const LinkSpec& l : doc.spec.links) {
    std::string type;
    const int n = net.findNode(l.from_block);
    if (n >= 0) {
      if (const PortSpec* p = net.node(n).block->findOutput(l.from_port)) type = p->type->name;
    }
    links.push_back({{"from", l.from_block + "." + l.from_port}, {"to", l.to_block + "." + l.to_port}, {"type", type}});
  }
  state["blocks"] = blocks;
  state["links"] = links;
}

}  // namespace designer
}  // namespace imagenets
