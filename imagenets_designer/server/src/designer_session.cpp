#include "designer_session.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include <boost/filesystem.hpp>
#include <ros/package.h>
#include <yaml-cpp/yaml.h>

#include "imagenets/graph.h"
#include "imagenets/net_writer.h"
#include "imagenets/registry.h"
#include "imagenets/inner_net.h"
#include "launch_export.h"
#include "net_state_json.h"
#include "port_data.h"
#include "yaml_json.h"

namespace imagenets {
namespace designer {

namespace fs = boost::filesystem;
using json = nlohmann::json;

namespace {

const json& field(const json& request, const std::string& name) {
  auto it = request.find(name);
  if (it == request.end()) {
    throw RequestError("request '" + request.value("op", std::string()) + "': missing field '" + name + "'");
  }
  return *it;
}

std::string stringField(const json& request, const std::string& name) {
  const json& v = field(request, name);
  if (!v.is_string()) {
    throw RequestError("request '" + request.value("op", std::string()) + "': field '" + name + "' must be a string");
  }
  return v.get<std::string>();
}

std::array<double, 2> positionOf(const json& v, const std::string& what) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    throw RequestError(what + ": a position is [x, y]");
  }
  return {v[0].get<double>(), v[1].get<double>()};
}

// "block.port" -> (block, port), as the net file writes it.
std::pair<std::string, std::string> splitEndpoint(const std::string& text, const std::string& what) {
  const auto dot = text.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) {
    throw RequestError(what + " '" + text + "' is not of the form block.port");
  }
  return {text.substr(0, dot), text.substr(dot + 1)};
}

// A property value in a request: text as a net file holds it; numbers and booleans are accepted.
std::string propertyText(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return formatNumber(v.get<double>());
  if (v.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + propertyText(v[i]);
    return out + "]";
  }
  throw RequestError("a property value is text, a number, a boolean or a list of numbers");
}

// The optional `properties: {name: text}` of a block in a request.
std::vector<PropertySetting> propertySettings(const json& item, const SourceLocation& loc) {
  std::vector<PropertySetting> out;
  auto it = item.find("properties");
  if (it == item.end() || it->is_null()) return out;
  if (!it->is_object()) throw RequestError("'properties' must be {name: text}");
  for (auto p = it->begin(); p != it->end(); ++p) out.push_back(PropertySetting{p.key(), propertyText(p.value()), loc});
  return out;
}

// "ImageFileSource" -> "image_file_source"
std::string nameFromType(const std::string& type) {
  const std::string base = type.substr(type.rfind('/') == std::string::npos ? 0 : type.rfind('/') + 1);
  std::string out;
  for (size_t i = 0; i < base.size(); ++i) {
    const char c = base[i];
    if (std::isupper(static_cast<unsigned char>(c))) {
      if (i > 0 && !std::isupper(static_cast<unsigned char>(base[i - 1]))) out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      out += c;
    }
  }
  return out.empty() ? "block" : out;
}

std::string uniqueName(const NetDocument& doc, const std::string& wanted, const std::set<std::string>& taken = {}) {
  if (!doc.findBlock(wanted) && !taken.count(wanted)) return wanted;
  for (int i = 2;; ++i) {
    const std::string name = wanted + "_" + std::to_string(i);
    if (!doc.findBlock(name) && !taken.count(name)) return name;
  }
}

// The engine parses a feedback map (one definition of its keys and checks): the request's map is
// written into a one-block net and read back.
FeedbackSpec parseFeedback(const BlockSpec& block, const json& feedback, const NetSpec& spec) {
  if (!feedback.is_object()) throw RequestError("block '" + block.name + "': feedback must be an object or null");
  YAML::Node root;
  root["blocks"][block.name]["type"] = block.type;
  root["blocks"][block.name]["feedback"] = jsonToYaml(feedback);
  YAML::Emitter e;
  e << root;
  NetSpec parsed = parseNetText(e.c_str(), spec.origin, spec.base_dir);
  return *parsed.blocks.front().feedback;
}

// The spec without property values: equal for two nets that differ only in properties.
std::string structureOf(const NetSpec& spec) {
  NetSpec bare = spec;
  for (auto& b : bare.blocks) b.properties.clear();
  return bare.base_dir + "\n" + writeNetText(bare);
}

const std::string* findSetting(const BlockSpec& b, const std::string& property) {
  for (const auto& p : b.properties) {
    if (p.name == property) return &p.text;
  }
  return nullptr;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw NetError({path + ": cannot read net file: " + std::strerror(errno)});
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

DesignerSession::DesignerSession(Output& output, Options options) : out_(output), options_(std::move(options)) {
  for (const auto& r : options_.roots) roots_.add(r);
  // The example nets, images and markers of the block library.
  const std::string examples = ros::package::getPath("imagenets_blocks");
  if (!examples.empty()) roots_.add(examples + "/config");
  doc_ = NetDocument::empty("(new net)", roots_.roots().empty() ? fs::current_path().string() : roots_.roots().front());
  rebuild(doc_);
  saved_text_ = doc_.text();
}

DesignerSession::~DesignerSession() {
  std::lock_guard<std::mutex> lock(executor_mutex_);
  executor_.reset();
}

bool DesignerSession::openStartupNet(const std::string& path) {
  const std::string absolute = fs::weakly_canonical(fs::absolute(path)).string();
  roots_.add(fs::path(absolute).parent_path().string());
  if (!fs::exists(absolute)) {
    // A new net, saved under that name.
    file_ = absolute;
    doc_ = NetDocument::empty(absolute, fs::path(absolute).parent_path().string());
    rebuild(doc_);
    saved_text_ = doc_.text();
    return true;
  }
  try {
    loadFile(absolute);
    return true;
  } catch (const NetError& e) {
    errors_ = e.errors();
    file_ = absolute;
    doc_ = NetDocument::empty(absolute, fs::path(absolute).parent_path().string());
    rebuild(doc_);
    saved_text_ = doc_.text();
    return false;
  }
}

std::string DesignerSession::baseDir() const { return doc_.spec.base_dir; }

void DesignerSession::loadFile(const std::string& path) {
  NetDocument next = NetDocument::fromText(readFile(path), path, fs::path(path).parent_path().string());
  rebuild(next);
  doc_ = std::move(next);
  file_ = path;
  saved_text_ = doc_.text();
  ++document_;
  undo_.clear();
  redo_.clear();
  errors_.clear();
  changed();
}

void DesignerSession::rebuild(const NetDocument& doc) {
  auto net = Net::build(doc.spec);
  auto executor = std::make_unique<Executor>(std::move(net), ExecutorOptions{options_.threads});
  // Run events go to every tab as they happen (observers run on pool threads: broadcast only queues).
  executor->addObserver([this](const RunEvent& e) {
    out_.broadcast(jsonText(eventJson(e)));
    if (e.kind == RunEventKind::BlockCached) {
      std::lock_guard<std::mutex> lock(cached_mutex_);
      cached_.push_back(e.block);
    }
  });
  {
    std::lock_guard<std::mutex> lock(executor_mutex_);
    executor_.swap(executor);
  }
  encoded_.clear();
}

void DesignerSession::setExecutorProperty(const NetDocument& doc, const std::string& block,
                                          const std::string& property, const std::string* text) {
  const int n = executor_->net().findNode(block);
  if (n < 0) throw RequestError("no block named '" + block + "'");
  const Block& instance = *executor_->net().node(n).block;
  const PropertySpec* spec = instance.findProperty(property);
  const std::string where = doc.spec.origin + ": block '" + block + "' (" +
                            (instance.info() ? instance.info()->type : std::string("?")) + "): ";
  if (!spec) {
    std::string known;
    for (const auto& p : instance.propertySpecs()) known += (known.empty() ? "" : ", ") + p.name();
    throw NetError({where + "unknown property '" + property + "' (known: " + (known.empty() ? "none" : known) + ")"});
  }
  PropertyValue value;
  try {
    // Relative paths name files beside the net file, as when the net is loaded.
    value = text ? spec->parse(*text, doc.spec.base_dir) : spec->defaultValue();
  } catch (const std::exception& e) {
    throw NetError({where + "property '" + property + "': " + e.what()});
  }
  executor_->setProperty(block, property, value);
}

bool DesignerSession::configurationChanged(const NetDocument& previous, const NetDocument& next) const {
  for (const BlockSpec& b : next.spec.blocks) {
    const BlockSpec* old = previous.findBlock(b.name);
    if (!old) return true;
    auto settings = [](const BlockSpec& spec) {
      std::map<std::string, std::string> out;
      for (const auto& p : spec.properties) out[p.name] = p.text;
      return out;
    };
    if (settings(b) == settings(*old)) continue;
    const int n = executor_->net().findNode(b.name);
    if (n < 0) return true;
    const Block& instance = *executor_->net().node(n).block;
    // A sub-net is loaded when its block is configured: a new property value needs a new build.
    if (instance.subNet()) return true;
    // So does a property that decides the block's ports (e.g. a number of inputs).
    auto fresh = BlockRegistry::instance().create(b.type);
    try {
      for (const auto& p : b.properties) {
        const PropertySpec* spec = fresh->findProperty(p.name);
        if (!spec) return false;  // setExecutorProperty names it
        fresh->setProperty(p.name, spec->parse(p.text, next.spec.base_dir));
      }
      LoadContext::Scope scope(next.spec);
      fresh->configure();
    } catch (const std::exception&) {
      return true;  // the build reports the engine's own message
    }
    auto samePorts = [](const std::vector<PortSpec>& a, const std::vector<PortSpec>& b) {
      std::vector<std::pair<std::string, const PortType*>> x, y;
      for (const auto& p : a) {
        if (p.name != "feedback_trace") x.emplace_back(p.name, p.type);
      }
      for (const auto& p : b) {
        if (p.name != "feedback_trace") y.emplace_back(p.name, p.type);
      }
      return x == y;
    };
    if (!samePorts(fresh->inputs(), instance.inputs()) || !samePorts(fresh->outputs(), instance.outputs())) return true;
  }
  return false;
}

void DesignerSession::apply(NetDocument next, const std::string& merge, bool notify) {
  // The state every tab gets holds the net's text: an edit that cannot be written is refused
  // here, before it is installed, rather than leaving a net no tab can be shown.
  next.text();
  NetDocument previous = doc_;
  install(std::move(next));
  if (merge.empty() || undo_.empty() || undo_.back().merge != merge || !redo_.empty()) {
    undo_.push_back({std::move(previous), merge});
  }
  redo_.clear();
  if (notify) {
    changed();
  } else {
    ++revision_;  // the caller pushes the state
  }
}

void DesignerSession::install(NetDocument next) {
  const NetDocument& previous = doc_;
  if (structureOf(previous.spec) != structureOf(next.spec) || configurationChanged(previous, next)) {
    rebuild(next);
  } else {
    // Only properties (or positions) changed: the executor keeps its cache and re-runs only the
    // changed blocks and their downstream.
    std::vector<std::pair<std::string, std::string>> done;
    try {
      for (const BlockSpec& b : next.spec.blocks) {
        const BlockSpec& old = *previous.findBlock(b.name);
        std::set<std::string> names;
        for (const auto& p : b.properties) names.insert(p.name);
        for (const auto& p : old.properties) names.insert(p.name);
        for (const auto& name : names) {
          const std::string* now = findSetting(b, name);
          const std::string* before = findSetting(old, name);
          if ((now == nullptr) == (before == nullptr) && (!now || *now == *before)) continue;
          setExecutorProperty(next, b.name, name, now);
          done.emplace_back(b.name, name);
        }
      }
    } catch (...) {
      for (const auto& [block, name] : done) setExecutorProperty(previous, block, name, findSetting(*previous.findBlock(block), name));
      throw;
    }
  }
  doc_ = std::move(next);
}

void DesignerSession::changed() {
  ++revision_;
  out_.broadcast(jsonText(netState()));
}

BlockSpec& DesignerSession::block(NetDocument& doc, const std::string& name) const {
  BlockSpec* b = doc.findBlock(name);
  if (!b) throw RequestError("no block named '" + name + "'");
  return *b;
}

json DesignerSession::netState() const {
  json blocks = json::array(), links = json::array();
  const Net& net = executor_->net();
  for (const BlockSpec& b : doc_.spec.blocks) {
    json j = {{"name", b.name}, {"type", b.type}};
    auto pos = doc_.positions.find(b.name);
    j["position"] = pos == doc_.positions.end() ? json() : json{pos->second[0], pos->second[1]};
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
      j["stats"] = statsJson(executor_->stats(b.name));
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
  for (const LinkSpec& l : doc_.spec.links) {
    std::string type;
    const int n = net.findNode(l.from_block);
    if (n >= 0) {
      if (const PortSpec* p = net.node(n).block->findOutput(l.from_port)) type = p->type->name;
    }
    links.push_back({{"from", l.from_block + "." + l.from_port}, {"to", l.to_block + "." + l.to_port}, {"type", type}});
  }
  const std::string text = doc_.text();
  return {{"op", "net"},
          {"file", file_.empty() ? json() : json(file_)},
          {"dirty", text != saved_text_},
          {"yaml", text},
          {"revision", revision_},
          {"document", document_},
          {"can_undo", !undo_.empty()},
          {"can_redo", !redo_.empty()},
          {"auto_run", auto_run_},
          {"blocks", blocks},
          {"links", links},
          {"errors", errors_}};
}

// ---------------------------------------------------------------------------------------------
// Requests

const std::map<std::string, DesignerSession::Handler>& DesignerSession::handlers() {
  static const std::map<std::string, Handler> all{
      {"hello", &DesignerSession::opHello},
      {"registry", &DesignerSession::opRegistry},
      {"add_block", &DesignerSession::opAddBlock},
      {"remove_blocks", &DesignerSession::opRemoveBlocks},
      {"move_blocks", &DesignerSession::opMoveBlocks},
      {"add_link", &DesignerSession::opAddLink},
      {"remove_link", &DesignerSession::opRemoveLink},
      {"set_property", &DesignerSession::opSetProperty},
      {"set_feedback", &DesignerSession::opSetFeedback},
      {"rename_block", &DesignerSession::opRenameBlock},
      {"paste", &DesignerSession::opPaste},
      {"set_yaml", &DesignerSession::opSetYaml},
      {"undo", &DesignerSession::opUndo},
      {"redo", &DesignerSession::opRedo},
      {"auto_run", &DesignerSession::opAutoRun},
      {"run", &DesignerSession::opRun},
      {"run_all", &DesignerSession::opRunAll},
      {"run_block", &DesignerSession::opRunBlock},
      {"run_block_only", &DesignerSession::opRunBlockOnly},
      {"cancel", &DesignerSession::opCancel},
      {"open", &DesignerSession::opOpen},
      {"save", &DesignerSession::opSave},
      {"list_files", &DesignerSession::opListFiles},
      {"export_launch", &DesignerSession::opExportLaunch},
      {"export_graph", &DesignerSession::opExportGraph},
      {"subnet", &DesignerSession::opSubnet},
      {"subnet_open", &DesignerSession::opSubnetOpen},
      {"watch", &DesignerSession::opWatch},
  };
  return all;
}

void DesignerSession::handle(int client, const json& request) {
  const json id = request.is_object() && request.contains("id") ? request["id"] : json();
  try {
    if (!request.is_object()) throw RequestError("a request is a JSON object with \"op\" and \"id\"");
    auto op = request.find("op");
    if (op == request.end() || !op->is_string()) throw RequestError("request without a string \"op\"");
    auto it = handlers().find(op->get<std::string>());
    if (it == handlers().end()) {
      std::string known;
      for (const auto& kv : handlers()) known += (known.empty() ? "" : ", ") + kv.first;
      throw RequestError("unknown op '" + op->get<std::string>() + "' (known: " + known + ")");
    }
    json reply = (this->*(it->second))(client, request);
    reply["op"] = "reply";
    reply["id"] = id;
    reply["ok"] = true;
    out_.send(client, jsonText(reply));
  } catch (const std::exception& e) {
    json reply = id.is_null() ? json{{"op", "error"}} : json{{"op", "reply"}, {"id", id}, {"ok", false}};
    reply["error"] = e.what();
    out_.send(client, jsonText(reply));
  }
}

void DesignerSession::cancel() {
  std::lock_guard<std::mutex> lock(executor_mutex_);
  if (executor_) executor_->cancel();
}

void DesignerSession::disconnected(int client) {
  watches_.erase(client);
  for (auto it = sent_.begin(); it != sent_.end();) {
    it = it->first.first == client ? sent_.erase(it) : std::next(it);
  }
}

json DesignerSession::opHello(int, const json&) {
  static const json registry = registryJson();
  return {{"registry", registry}, {"net", netState()}};
}

json DesignerSession::opRegistry(int, const json&) {
  static const json registry = registryJson();
  return registry;
}

json DesignerSession::opAddBlock(int, const json& request) {
  NetDocument next = doc_;
  BlockSpec b;
  b.type = stringField(request, "type");
  b.name = request.contains("name") && !request["name"].is_null() ? stringField(request, "name")
                                                                   : uniqueName(doc_, nameFromType(b.type));
  b.loc = SourceLocation{doc_.spec.origin, 0};
  // A block that cannot be built with its defaults (a sub-net needs its net) comes with properties.
  b.properties = propertySettings(request, b.loc);
  if (request.contains("position") && !request["position"].is_null()) {
    next.positions[b.name] = positionOf(request["position"], "add_block");
  }
  next.spec.blocks.push_back(b);
  apply(std::move(next));
  return {{"name", b.name}};
}

json DesignerSession::opRemoveBlocks(int, const json& request) {
  const json& names = field(request, "names");
  if (!names.is_array()) throw RequestError("request 'remove_blocks': 'names' must be a list");
  NetDocument next = doc_;
  std::set<std::string> gone;
  for (const auto& n : names) {
    if (!n.is_string()) throw RequestError("request 'remove_blocks': names are strings");
    block(next, n.get<std::string>());
    gone.insert(n.get<std::string>());
  }
  auto& blocks = next.spec.blocks;
  blocks.erase(std::remove_if(blocks.begin(), blocks.end(), [&](const BlockSpec& b) { return gone.count(b.name) > 0; }),
               blocks.end());
  auto& links = next.spec.links;
  links.erase(std::remove_if(links.begin(), links.end(),
                             [&](const LinkSpec& l) { return gone.count(l.from_block) || gone.count(l.to_block); }),
              links.end());
  // A feedback scored by a removed block goes with it, like the links; so do initial values
  // read from a removed block's port.
  for (auto& b : blocks) {
    if (!b.feedback) continue;
    if (gone.count(b.feedback->score_block)) {
      b.feedback.reset();
      continue;
    }
    auto& initial = b.feedback->initial;
    initial.erase(std::remove_if(initial.begin(), initial.end(), [&](const FeedbackInitial& i) { return gone.count(i.block) > 0; }),
                  initial.end());
  }
  for (const auto& n : gone) next.positions.erase(n);
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opMoveBlocks(int, const json& request) {
  const json& positions = field(request, "positions");
  if (!positions.is_object()) throw RequestError("request 'move_blocks': 'positions' must be {name: [x, y]}");
  NetDocument next = doc_;
  for (auto it = positions.begin(); it != positions.end(); ++it) {
    block(next, it.key());
    next.positions[it.key()] = positionOf(it.value(), "block '" + it.key() + "'");
  }
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opAddLink(int, const json& request) {
  LinkSpec l;
  std::tie(l.from_block, l.from_port) = splitEndpoint(stringField(request, "from"), "'from'");
  std::tie(l.to_block, l.to_port) = splitEndpoint(stringField(request, "to"), "'to'");
  l.loc = SourceLocation{doc_.spec.origin, 0};
  NetDocument next = doc_;
  next.spec.links.push_back(l);
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opRemoveLink(int, const json& request) {
  const std::string from = stringField(request, "from"), to = stringField(request, "to");
  NetDocument next = doc_;
  auto& links = next.spec.links;
  auto it = std::find_if(links.begin(), links.end(), [&](const LinkSpec& l) {
    return l.from_block + "." + l.from_port == from && l.to_block + "." + l.to_port == to;
  });
  if (it == links.end()) throw RequestError("no link " + from + " -> " + to);
  links.erase(it);
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opSetProperty(int, const json& request) {
  const std::string name = stringField(request, "block"), property = stringField(request, "property");
  const json& value = field(request, "text");
  NetDocument next = doc_;
  BlockSpec& b = block(next, name);
  auto it = std::find_if(b.properties.begin(), b.properties.end(), [&](const PropertySetting& p) { return p.name == property; });
  if (value.is_null()) {
    if (it != b.properties.end()) b.properties.erase(it);  // back to the default
  } else if (it != b.properties.end()) {
    it->text = propertyText(value);
  } else {
    b.properties.push_back(PropertySetting{property, propertyText(value), SourceLocation{doc_.spec.origin, 0}});
  }
  // With auto_run the state goes out once, after the run, with the new stats.
  apply(std::move(next), "property " + name + "." + property, !auto_run_);
  json reply = json::object();
  if (auto_run_) reply["run"] = runAndReport(RunKind::OutOfDate, "");
  return reply;
}

json DesignerSession::opSetFeedback(int, const json& request) {
  NetDocument next = doc_;
  BlockSpec& b = block(next, stringField(request, "block"));
  const json& feedback = field(request, "feedback");
  if (feedback.is_null()) b.feedback.reset();
  else b.feedback = parseFeedback(b, feedback, next.spec);
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opRenameBlock(int, const json& request) {
  const std::string from = stringField(request, "block"), to = stringField(request, "name");
  NetDocument next = doc_;
  block(next, from).name = to;
  if (from != to && doc_.findBlock(to)) throw RequestError("a block named '" + to + "' exists already");
  for (auto& l : next.spec.links) {
    if (l.from_block == from) l.from_block = to;
    if (l.to_block == from) l.to_block = to;
  }
  for (auto& b : next.spec.blocks) {
    if (!b.feedback) continue;
    if (b.feedback->score_block == from) b.feedback->score_block = to;
    for (auto& initial : b.feedback->initial) {
      if (initial.block == from) initial.block = to;
    }
  }
  auto pos = next.positions.find(from);
  if (pos != next.positions.end()) {
    const auto p = pos->second;
    next.positions.erase(pos);
    next.positions[to] = p;
  }
  apply(std::move(next));
  return {{"name", to}};
}

json DesignerSession::opPaste(int, const json& request) {
  const json& blocks = field(request, "blocks");
  if (!blocks.is_array()) throw RequestError("request 'paste': 'blocks' must be a list");
  NetDocument next = doc_;
  std::map<std::string, std::string> names;
  std::set<std::string> taken;
  for (const auto& item : blocks) {
    if (!item.is_object()) throw RequestError("request 'paste': each block is {name, type, properties, position, feedback}");
    const std::string old = stringField(item, "name");
    const std::string name = uniqueName(doc_, old, taken);
    taken.insert(name);
    names[old] = name;
  }
  for (const auto& item : blocks) {
    BlockSpec b;
    b.name = names[stringField(item, "name")];
    b.type = stringField(item, "type");
    b.loc = SourceLocation{doc_.spec.origin, 0};
    b.properties = propertySettings(item, b.loc);
    if (item.contains("position") && !item["position"].is_null()) {
      next.positions[b.name] = positionOf(item["position"], "block '" + b.name + "'");
    }
    if (item.contains("feedback") && !item["feedback"].is_null()) {
      json fb = item["feedback"];
      // Block names inside the feedback (the score, initial values from ports) follow the paste.
      auto rename = [&](json& endpoint) {
        if (!endpoint.is_string()) return;
        const std::string text = endpoint.get<std::string>();
        const auto dot = text.find('.');
        if (dot != std::string::npos && names.count(text.substr(0, dot))) endpoint = names[text.substr(0, dot)] + text.substr(dot);
      };
      if (fb.contains("score")) rename(fb["score"]);
      if (fb.contains("initial")) {
        if (fb["initial"].is_array()) {
          for (auto& i : fb["initial"]) rename(i);
        } else {
          rename(fb["initial"]);
        }
      }
      b.feedback = parseFeedback(b, fb, next.spec);
    }
    next.spec.blocks.push_back(b);
  }
  if (request.contains("links") && request["links"].is_array()) {
    for (const auto& item : request["links"]) {
      std::string from, to;
      if (item.is_object()) {
        from = stringField(item, "from");
        to = stringField(item, "to");
      } else {
        throw RequestError("request 'paste': each link is {from: block.port, to: block.port}");
      }
      LinkSpec l;
      std::tie(l.from_block, l.from_port) = splitEndpoint(from, "'from'");
      std::tie(l.to_block, l.to_port) = splitEndpoint(to, "'to'");
      if (names.count(l.from_block)) l.from_block = names[l.from_block];
      if (names.count(l.to_block)) l.to_block = names[l.to_block];
      l.loc = SourceLocation{doc_.spec.origin, 0};
      next.spec.links.push_back(l);
    }
  }
  apply(std::move(next));
  return {{"names", names}};
}

json DesignerSession::opSetYaml(int, const json& request) {
  NetDocument next = NetDocument::fromText(stringField(request, "text"), doc_.spec.origin, doc_.spec.base_dir);
  for (const auto& kv : doc_.positions) {
    if (next.findBlock(kv.first) && !next.positions.count(kv.first)) next.positions.insert(kv);
  }
  apply(std::move(next));
  return json::object();
}

json DesignerSession::opUndo(int, const json&) { return step(undo_, redo_, "undo"); }
json DesignerSession::opRedo(int, const json&) { return step(redo_, undo_, "redo"); }

json DesignerSession::step(std::vector<Snapshot>& from, std::vector<Snapshot>& to, const std::string& what) {
  if (from.empty()) throw RequestError("nothing to " + what);
  NetDocument current = doc_;
  install(from.back().doc);
  from.pop_back();
  to.push_back({std::move(current)});
  changed();
  return json::object();
}

json DesignerSession::opAutoRun(int, const json& request) {
  const json& on = field(request, "on");
  if (!on.is_boolean()) throw RequestError("request 'auto_run': 'on' must be true or false");
  auto_run_ = on.get<bool>();
  changed();
  return json::object();
}

json DesignerSession::runReport(const RunReport& report) const {
  return {{"ran", report.ran}, {"failed", report.failed}, {"not_run", report.not_run}, {"cancelled", report.cancelled}};
}

json DesignerSession::runAndReport(RunKind kind, const std::string& block) {
  {
    std::lock_guard<std::mutex> lock(cached_mutex_);
    cached_.clear();
  }
  RunReport report;
  switch (kind) {
    case RunKind::OutOfDate: report = executor_->run(); break;
    case RunKind::All: report = executor_->runAll(); break;
    case RunKind::FromBlock: report = executor_->runBlock(block); break;
    case RunKind::BlockOnly: report = executor_->runBlockOnly(block); break;
  }
  ++run_count_;
  // The new values first: a page shows a preview before it digests the new state.
  sendPortData();
  out_.broadcast(jsonText(netState()));  // stats
  json reply = runReport(report);
  std::lock_guard<std::mutex> lock(cached_mutex_);
  reply["cached"] = cached_;
  return reply;
}

json DesignerSession::opRun(int, const json&) { return runAndReport(RunKind::OutOfDate, ""); }
json DesignerSession::opRunAll(int, const json&) { return runAndReport(RunKind::All, ""); }

json DesignerSession::opRunBlock(int, const json& request) {
  const std::string name = stringField(request, "block");
  if (executor_->net().findNode(name) < 0) throw RequestError("no block named '" + name + "'");
  return runAndReport(RunKind::FromBlock, name);
}

json DesignerSession::opRunBlockOnly(int, const json& request) {
  const std::string name = stringField(request, "block");
  if (executor_->net().findNode(name) < 0) throw RequestError("no block named '" + name + "'");
  return runAndReport(RunKind::BlockOnly, name);
}

json DesignerSession::opCancel(int, const json&) {
  cancel();
  return json::object();
}

json DesignerSession::opOpen(int, const json& request) {
  const std::string path = roots_.check(stringField(request, "path"), baseDir());
  loadFile(path);
  return {{"file", path}};
}

json DesignerSession::opSave(int, const json& request) {
  std::string target = file_;
  if (request.contains("path") && !request["path"].is_null()) target = stringField(request, "path");
  if (target.empty()) throw RequestError("the net has no file yet: save it with a path");
  target = roots_.check(target, baseDir());
  NetDocument next = doc_;
  next.moveTo(target, fs::path(target).parent_path().string());
  const std::string text = next.text();
  // What is written must load: the engine's parser is the judge (an empty net is refused here).
  parseNetText(text, target, next.spec.base_dir);
  const std::string tmp = target + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out.flush()) throw RequestError("cannot write '" + tmp + "': " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), target.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw RequestError("cannot write '" + target + "': " + std::strerror(errno));
  }
  next.rebase(text);
  install(std::move(next));
  file_ = target;
  saved_text_ = text;
  errors_.clear();
  changed();
  // Open file dialogs in other tabs list the folder again.
  out_.broadcast(jsonText({{"op", "files"}, {"dir", fs::path(target).parent_path().string()}, {"file", target}}));
  return {{"file", target}};
}

json DesignerSession::opListFiles(int, const json& request) {
  std::string dir = baseDir();
  if (request.contains("dir") && !request["dir"].is_null()) dir = stringField(request, "dir");
  dir = roots_.check(dir, baseDir());
  if (!fs::is_directory(dir)) throw RequestError("'" + dir + "' is not a folder");
  std::vector<std::pair<bool, std::string>> entries;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    entries.emplace_back(!fs::is_directory(e.path()), name);
  }
  std::sort(entries.begin(), entries.end());
  json list = json::array();
  for (const auto& [file, name] : entries) list.push_back({{"name", name}, {"dir", !file}});
  return {{"dir", dir}, {"entries", list}, {"roots", roots_.roots()}};
}

json DesignerSession::opExportLaunch(int, const json&) { return {{"text", exportLaunch(doc_.spec)}}; }

json DesignerSession::opExportGraph(int, const json& request) {
  const bool expand = request.value("expand", false);
  return {{"svg", renderDot(toDot(executor_->net(), expand), "svg")}};
}

json DesignerSession::opSubnet(int, const json& request) {
  const std::string name = stringField(request, "block");
  const int n = executor_->net().findNode(name);
  if (n < 0) throw RequestError("no block named '" + name + "'");
  const Block& b = *executor_->net().node(n).block;
  if (!b.subNet()) throw RequestError("block '" + name + "' (" + (b.info() ? b.info()->type : "?") + ") has no sub-net");
  const auto* inner = dynamic_cast<const InnerNet*>(&b);
  json state = builtNetState(*b.subNet(), inner ? inner->innerExecutor() : nullptr);
  state["block"] = name;
  const std::string inline_yaml = b.findProperty("net_yaml") ? std::get<std::string>(b.propertyValue("net_yaml")) : "";
  try {
    state["yaml"] = inline_yaml.empty() ? readFile(b.subNet()->origin()) : inline_yaml;
  } catch (const NetError&) {
    state["yaml"] = "";
  }
  return {{"net", state}};
}

json DesignerSession::opSubnetOpen(int, const json& request) {
  const std::string name = stringField(request, "block");
  const int n = executor_->net().findNode(name);
  if (n < 0) throw RequestError("no block named '" + name + "'");
  const Block& b = *executor_->net().node(n).block;
  if (!b.subNet()) throw RequestError("block '" + name + "' has no sub-net");
  const std::string file = b.findProperty("net") ? std::get<std::string>(b.propertyValue("net")) : "";
  if (file.empty()) throw RequestError("the sub-net of block '" + name + "' is written inline (net_yaml): it has no file to open");
  const std::string path = roots_.check(file, baseDir());
  loadFile(path);
  return {{"file", path}};
}

json DesignerSession::opWatch(int client, const json& request) {
  const json& ports = field(request, "ports");
  if (!ports.is_array()) throw RequestError("request 'watch': 'ports' must be a list of block.port");
  const std::string mode = request.value("mode", std::string("preview"));
  if (mode != "preview" && mode != "full") throw RequestError("request 'watch': mode '" + mode + "' is neither preview nor full");
  std::set<std::string> set;
  for (const auto& p : ports) {
    if (!p.is_string()) throw RequestError("request 'watch': ports are strings block.port");
    executor_->net().resolveOutput(p.get<std::string>());  // NetError naming the block or port
    set.insert(p.get<std::string>());
  }
  // Ports no longer watched are forgotten, so watching one again sends its value again.
  for (const auto& old : watches_[client][mode]) {
    if (!set.count(old)) sent_.erase({client, old + "|" + mode});
  }
  watches_[client][mode] = set;
  sendPortData(client);
  return json::object();
}

void DesignerSession::sendPortData() {
  for (const auto& kv : watches_) sendPortData(kv.first);
}

void DesignerSession::sendPortData(int client) {
  auto w = watches_.find(client);
  if (w == watches_.end()) return;
  for (const auto& [mode, ports] : w->second) {
    for (const auto& port : ports) {
      Value value;
      try {
        value = executor_->output(port);
      } catch (const NetError&) {
        continue;  // the block went away in an edit
      }
      const std::string slot = port + "|" + mode;
      auto sent = sent_.find({client, slot});
      if (sent != sent_.end() && sent->second == value.data) continue;
      auto& cached = encoded_[slot];
      if (!cached.second || cached.first != value.data) {
        json header = {{"port", port}, {"revision", revision_}, {"run", run_count_}, {"document", document_}};
        try {
          cached = {value.data, std::make_shared<const std::string>(encodePortFrame(value, mode, header))};
        } catch (const std::exception& e) {
          header["error"] = std::string("cannot show the value: ") + e.what();
          cached = {value.data, std::make_shared<const std::string>(encodePortFrame(Value(), mode, header))};
        }
      }
      sent_[{client, slot}] = value.data;
      out_.sendPortData(client, slot, cached.second);
    }
  }
}

}  // namespace designer
}  // namespace imagenets
