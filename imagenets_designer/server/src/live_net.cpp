#include "live_net.h"

#include <set>

#include "imagenets/net_writer.h"
#include "net_state_json.h"
#include "request_error.h"

namespace imagenets {
namespace designer {

namespace {

// The spec without property values: equal for two nets that differ only in properties.
std::string structureOf(const NetSpec& spec) {
  NetSpec bare = spec;
  for (auto& b : bare.blocks) b.properties.clear();
  return bare.base_dir + "\n" + writeNetText(bare);
}

// The names of the properties whose settings differ between two versions of one block.
std::set<std::string> changedSettings(const BlockSpec& before, const BlockSpec& now) {
  std::set<std::string> names, changed;
  for (const auto& p : before.properties) names.insert(p.name);
  for (const auto& p : now.properties) names.insert(p.name);
  for (const auto& name : names) {
    const PropertySetting* a = before.findSetting(name);
    const PropertySetting* b = now.findSetting(name);
    if ((a == nullptr) != (b == nullptr) || (a && a->text != b->text)) changed.insert(name);
  }
  return changed;
}

}  // namespace

LiveNet::LiveNet(DesignerOutput& out, int threads) : out_(out), threads_(threads) {}

LiveNet::~LiveNet() {
  std::lock_guard<std::mutex> lock(executor_mutex_);
  executor_.reset();
}

void LiveNet::rebuild(const NetDocument& doc) {
  auto net = Net::build(doc.spec);
  auto executor = std::make_unique<Executor>(std::move(net), ExecutorOptions{threads_});
  // Observers run on pool threads: broadcast only queues.
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
  watches_.newExecutor();
}

PropertyValues LiveNet::valuesOf(const NetDocument& doc, const BlockSpec& b, const std::set<std::string>& names) const {
  const Block& instance = block(b.name);
  PropertyValues values;
  try {
    for (const auto& name : names) {
      const PropertySetting* setting = b.findSetting(name);
      // Relative paths name files beside the net file, as when the net is loaded.
      values[name] = setting ? instance.parseProperty(name, setting->text, doc.spec.base_dir)
                             : instance.propertySpec(name).defaultValue();
    }
  } catch (const PropertyError& e) {
    throw NetError({doc.spec.origin + ": block '" + b.name + "' (" + b.type + "): " + e.what()});
  }
  return values;
}

void LiveNet::install(const NetDocument& previous, const NetDocument& next) {
  if (structureOf(previous.spec) != structureOf(next.spec)) return rebuild(next);
  // Only properties (or positions) changed: the executor keeps its cache, unless a change alters
  // a block's ports. What was applied is undone when a later block refuses its values.
  std::vector<std::pair<std::string, PropertyValues>> undo;
  try {
    for (const BlockSpec& b : next.spec.blocks) {
      const BlockSpec& old = previous.spec.block(b.name);
      const std::set<std::string> names = changedSettings(old, b);
      if (names.empty()) continue;
      const PropertyValues before = valuesOf(previous, old, names);
      if (executor_->setProperties(b.name, valuesOf(next, b, names)) == Executor::PropertyChange::NeedsRebuild) {
        rebuild(next);
        return;
      }
      undo.emplace_back(b.name, before);
    }
  } catch (...) {
    for (const auto& [block, values] : undo) executor_->setProperties(block, values);
    throw;
  }
}

LiveNet::Run LiveNet::run(RunKind kind, const std::string& block) {
  if (kind == RunKind::FromBlock || kind == RunKind::BlockOnly) this->block(block);
  {
    std::lock_guard<std::mutex> lock(cached_mutex_);
    cached_.clear();
  }
  Run run;
  switch (kind) {
    case RunKind::OutOfDate: run.report = executor_->run(); break;
    case RunKind::All: run.report = executor_->runAll(); break;
    case RunKind::FromBlock: run.report = executor_->runBlock(block); break;
    case RunKind::BlockOnly: run.report = executor_->runBlockOnly(block); break;
  }
  ++runs_;
  std::lock_guard<std::mutex> lock(cached_mutex_);
  run.cached = cached_;
  return run;
}

void LiveNet::cancel() {
  std::lock_guard<std::mutex> lock(executor_mutex_);
  if (executor_) executor_->cancel();
}

const Block& LiveNet::block(const std::string& name) const {
  const int n = net().findNode(name);
  if (n < 0) throw RequestError("no block named '" + name + "'");
  return *net().node(n).block;
}

void LiveNet::watch(int client, const std::string& mode, const std::set<std::string>& ports) {
  for (const auto& p : ports) net().resolveOutput(p);  // NetError naming the block or port
  watches_.watch(client, mode, ports);
}

void LiveNet::sendPortData(int client, const nlohmann::json& header) { watches_.send(client, *executor_, out_, header); }

void LiveNet::sendPortData(const nlohmann::json& header) { watches_.send(*executor_, out_, header); }

}  // namespace designer
}  // namespace imagenets
