#include "designer_session.h"

#include <optional>
#include <set>
#include <utility>

#include <boost/filesystem.hpp>
#include <ros/package.h>

#include "imagenets/graph.h"
#include "imagenets/inner_net.h"
#include "imagenets/registry.h"
#include "launch_export.h"
#include "net_edits.h"
#include "net_state_json.h"
#include "request_fields.h"

namespace imagenets {
namespace designer {

namespace fs = boost::filesystem;
using json = nlohmann::json;

DesignerSession::DesignerSession(Output& output, Options options) : out_(output), live_(output, options.threads) {
  for (const auto& r : options.roots) files_.roots().add(r);
  // The example nets, images and markers of the block library.
  const std::string examples = ros::package::getPath("imagenets_blocks");
  if (!examples.empty()) files_.roots().add(examples + "/config");
  const auto& roots = files_.roots().roots();
  startEmpty("(new net)", roots.empty() ? fs::current_path().string() : roots.front());
}

void DesignerSession::startEmpty(const std::string& origin, const std::string& dir) {
  doc_ = NetDocument::empty(origin, dir);
  live_.rebuild(doc_);
  saved_text_ = doc_.text();
}

bool DesignerSession::openStartupNet(const std::string& path) {
  const std::string absolute = fs::weakly_canonical(fs::absolute(path)).string();
  const std::string dir = fs::path(absolute).parent_path().string();
  files_.roots().add(dir);
  if (!fs::exists(absolute)) {
    // A new net, saved under that name.
    file_ = absolute;
    startEmpty(absolute, dir);
    return true;
  }
  try {
    loadFile(absolute);
    return true;
  } catch (const NetError& e) {
    errors_ = e.errors();
    file_ = absolute;
    startEmpty(absolute, dir);
    return false;
  }
}

void DesignerSession::loadFile(const std::string& path) {
  NetDocument next = files_.load(path);
  live_.rebuild(next);
  doc_ = std::move(next);
  file_ = path;
  saved_text_ = doc_.text();
  ++document_;
  history_.clear();
  errors_.clear();
  changed();
}

void DesignerSession::apply(NetDocument next, const std::string& merge, bool notify) {
  // The state every tab gets holds the net's text: an edit that cannot be written is refused
  // here, before it is installed, rather than leaving a net no tab can be shown.
  next.text();
  live_.install(doc_, next);
  history_.edited(std::exchange(doc_, std::move(next)), merge);
  if (notify) {
    changed();
  } else {
    ++revision_;  // the caller pushes the state
  }
}

json DesignerSession::step(EditHistory::Direction direction) {
  NetDocument next = history_.target(direction);
  live_.install(doc_, next);
  history_.stepped(direction, std::exchange(doc_, std::move(next)));
  changed();
  return json::object();
}

void DesignerSession::changed() {
  ++revision_;
  out_.broadcast(jsonText(netState()));
}

json DesignerSession::netState() const {
  const std::string text = doc_.text();
  json state = {{"op", "net"},
                {"file", file_.empty() ? json() : json(file_)},
                {"dirty", text != saved_text_},
                {"yaml", text},
                {"revision", revision_},
                {"document", document_},
                {"can_undo", history_.canUndo()},
                {"can_redo", history_.canRedo()},
                {"auto_run", auto_run_},
                {"errors", errors_}};
  addDocument(state, doc_, live_.executor());
  return state;
}

json DesignerSession::portDataHeader() const {
  return {{"revision", revision_}, {"run", live_.runs()}, {"document", document_}};
}

json DesignerSession::runAndReport(LiveNet::RunKind kind, const std::string& block) {
  const LiveNet::Run run = live_.run(kind, block);
  // The new values first: a page shows a preview before it digests the new state.
  live_.sendPortData(portDataHeader());
  out_.broadcast(jsonText(netState()));  // stats
  const RunReport& r = run.report;
  return {{"ran", r.ran}, {"failed", r.failed}, {"not_run", r.not_run}, {"cancelled", r.cancelled}, {"cached", run.cached}};
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

json DesignerSession::opHello(int, const json&) {
  static const json registry = registryJson();
  return {{"registry", registry}, {"net", netState()}};
}

json DesignerSession::opRegistry(int, const json&) {
  static const json registry = registryJson();
  return registry;
}

json DesignerSession::opAddBlock(int, const json& request) {
  BlockSpec b;
  b.type = stringField(request, "type");
  b.name = request.contains("name") && !request["name"].is_null() ? stringField(request, "name")
                                                                   : edits::freeName(doc_, edits::nameFromType(b.type));
  b.loc = SourceLocation{doc_.spec.origin, 0};
  // A block that cannot be built with its defaults (a sub-net needs its net) comes with properties.
  b.properties = propertySettings(request, b.loc);
  std::optional<edits::Position> position;
  if (request.contains("position") && !request["position"].is_null()) position = positionOf(request["position"], "add_block");
  const std::string name = b.name;
  apply(edits::addBlock(doc_, std::move(b), position));
  return {{"name", name}};
}

json DesignerSession::opRemoveBlocks(int, const json& request) {
  const json& names = field(request, "names");
  if (!names.is_array()) throw RequestError("request 'remove_blocks': 'names' must be a list");
  std::set<std::string> gone;
  for (const auto& n : names) {
    if (!n.is_string()) throw RequestError("request 'remove_blocks': names are strings");
    gone.insert(n.get<std::string>());
  }
  apply(edits::removeBlocks(doc_, gone));
  return json::object();
}

json DesignerSession::opMoveBlocks(int, const json& request) {
  const json& positions = field(request, "positions");
  if (!positions.is_object()) throw RequestError("request 'move_blocks': 'positions' must be {name: [x, y]}");
  std::map<std::string, edits::Position> moved;
  for (auto it = positions.begin(); it != positions.end(); ++it) {
    edits::block(doc_, it.key());
    moved[it.key()] = positionOf(it.value(), "block '" + it.key() + "'");
  }
  apply(edits::moveBlocks(doc_, moved));
  return json::object();
}

json DesignerSession::opAddLink(int, const json& request) {
  apply(edits::addLink(doc_, stringField(request, "from"), stringField(request, "to")));
  return json::object();
}

json DesignerSession::opRemoveLink(int, const json& request) {
  apply(edits::removeLink(doc_, stringField(request, "from"), stringField(request, "to")));
  return json::object();
}

json DesignerSession::opSetProperty(int, const json& request) {
  const std::string name = stringField(request, "block"), property = stringField(request, "property");
  const json& value = field(request, "text");
  std::optional<std::string> text;
  if (!value.is_null()) text = propertyText(value);
  // With auto_run the state goes out once, after the run, with the new stats.
  apply(edits::setProperty(doc_, name, property, text), "property " + name + "." + property, !auto_run_);
  json reply = json::object();
  if (auto_run_) reply["run"] = runAndReport(LiveNet::RunKind::OutOfDate);
  return reply;
}

json DesignerSession::opSetFeedback(int, const json& request) {
  const BlockSpec& b = edits::block(doc_, stringField(request, "block"));
  const json& feedback = field(request, "feedback");
  std::optional<FeedbackSpec> spec;
  if (!feedback.is_null()) spec = feedbackOf(b, feedback, doc_.spec);
  apply(edits::setFeedback(doc_, b.name, std::move(spec)));
  return json::object();
}

json DesignerSession::opRenameBlock(int, const json& request) {
  const std::string from = stringField(request, "block"), to = stringField(request, "name");
  apply(edits::renameBlock(doc_, from, to));
  return {{"name", to}};
}

json DesignerSession::opPaste(int, const json& request) {
  const json& blocks = field(request, "blocks");
  if (!blocks.is_array()) throw RequestError("request 'paste': 'blocks' must be a list");
  std::vector<edits::PastedBlock> pasted;
  for (const auto& item : blocks) {
    if (!item.is_object()) throw RequestError("request 'paste': each block is {name, type, properties, position, feedback}");
    edits::PastedBlock p;
    p.spec.name = stringField(item, "name");
    p.spec.type = stringField(item, "type");
    p.spec.properties = propertySettings(item, SourceLocation{doc_.spec.origin, 0});
    if (item.contains("position") && !item["position"].is_null()) {
      p.position = positionOf(item["position"], "block '" + p.spec.name + "'");
    }
    if (item.contains("feedback") && !item["feedback"].is_null()) p.spec.feedback = feedbackOf(p.spec, item["feedback"], doc_.spec);
    pasted.push_back(std::move(p));
  }
  std::vector<std::pair<std::string, std::string>> links;
  if (request.contains("links") && request["links"].is_array()) {
    for (const auto& item : request["links"]) {
      if (!item.is_object()) throw RequestError("request 'paste': each link is {from: block.port, to: block.port}");
      links.emplace_back(stringField(item, "from"), stringField(item, "to"));
    }
  }
  edits::Pasted result = edits::paste(doc_, pasted, links);
  apply(std::move(result.doc));
  return {{"names", result.names}};
}

json DesignerSession::opSetYaml(int, const json& request) {
  apply(edits::setText(doc_, stringField(request, "text")));
  return json::object();
}

json DesignerSession::opUndo(int, const json&) { return step(EditHistory::Direction::Undo); }
json DesignerSession::opRedo(int, const json&) { return step(EditHistory::Direction::Redo); }

json DesignerSession::opAutoRun(int, const json& request) {
  const json& on = field(request, "on");
  if (!on.is_boolean()) throw RequestError("request 'auto_run': 'on' must be true or false");
  auto_run_ = on.get<bool>();
  changed();
  return json::object();
}

json DesignerSession::opRun(int, const json&) { return runAndReport(LiveNet::RunKind::OutOfDate); }
json DesignerSession::opRunAll(int, const json&) { return runAndReport(LiveNet::RunKind::All); }

json DesignerSession::opRunBlock(int, const json& request) {
  return runAndReport(LiveNet::RunKind::FromBlock, stringField(request, "block"));
}

json DesignerSession::opRunBlockOnly(int, const json& request) {
  return runAndReport(LiveNet::RunKind::BlockOnly, stringField(request, "block"));
}

json DesignerSession::opCancel(int, const json&) {
  cancel();
  return json::object();
}

json DesignerSession::opOpen(int, const json& request) {
  const std::string path = files_.check(stringField(request, "path"), baseDir());
  loadFile(path);
  return {{"file", path}};
}

json DesignerSession::opSave(int, const json& request) {
  std::string target = file_;
  if (request.contains("path") && !request["path"].is_null()) target = stringField(request, "path");
  if (target.empty()) throw RequestError("the net has no file yet: save it with a path");
  target = files_.check(target, baseDir());
  NetFiles::Saved saved = files_.save(doc_, target);
  live_.install(doc_, saved.doc);
  doc_ = std::move(saved.doc);
  file_ = target;
  saved_text_ = saved.text;
  errors_.clear();
  changed();
  // Open file dialogs in other tabs list the folder again.
  out_.broadcast(jsonText({{"op", "files"}, {"dir", fs::path(target).parent_path().string()}, {"file", target}}));
  return {{"file", target}};
}

json DesignerSession::opListFiles(int, const json& request) {
  std::string dir = baseDir();
  if (request.contains("dir") && !request["dir"].is_null()) dir = stringField(request, "dir");
  return files_.list(files_.check(dir, baseDir()));
}

json DesignerSession::opExportLaunch(int, const json&) { return {{"text", exportLaunch(doc_.spec)}}; }

json DesignerSession::opExportGraph(int, const json& request) {
  const bool expand = request.value("expand", false);
  return {{"svg", renderDot(toDot(live_.net(), expand), "svg")}};
}

json DesignerSession::opSubnet(int, const json& request) {
  const std::string name = stringField(request, "block");
  const Block& b = live_.block(name);
  if (!b.subNet()) throw RequestError("block '" + name + "' (" + (b.info() ? b.info()->type : "?") + ") has no sub-net");
  const auto* inner = dynamic_cast<const InnerNet*>(&b);
  json state = builtNetState(*b.subNet(), inner ? inner->innerExecutor() : nullptr);
  state["block"] = name;
  const std::string inline_yaml = b.findProperty("net_yaml") ? std::get<std::string>(b.propertyValue("net_yaml")) : "";
  try {
    state["yaml"] = inline_yaml.empty() ? NetFiles::read(b.subNet()->origin()) : inline_yaml;
  } catch (const NetError&) {
    state["yaml"] = "";
  }
  return {{"net", state}};
}

json DesignerSession::opSubnetOpen(int, const json& request) {
  const std::string name = stringField(request, "block");
  const Block& b = live_.block(name);
  if (!b.subNet()) throw RequestError("block '" + name + "' has no sub-net");
  const std::string file = b.findProperty("net") ? std::get<std::string>(b.propertyValue("net")) : "";
  if (file.empty()) throw RequestError("the sub-net of block '" + name + "' is written inline (net_yaml): it has no file to open");
  const std::string path = files_.check(file, baseDir());
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
    set.insert(p.get<std::string>());
  }
  live_.watch(client, mode, set);
  live_.sendPortData(client, portDataHeader());
  return json::object();
}

}  // namespace designer
}  // namespace imagenets
