#include "live_net.h"

#include <map>

#include "imagenets/net_writer.h"
#include "imagenets/registry.h"
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

const std::string* findSetting(const BlockSpec& b, const std::string& property) {
  for (const auto& p : b.properties) {
    if (p.name == property) return &p.text;
  }
  return nullptr;
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

void LiveNet::setProperty(const NetDocument& doc, const std::string& block, const std::string& property,
                          const std::string* text) {
  const Block& instance = this->block(block);
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

bool LiveNet::configurationChanged(const NetDocument& previous, const NetDocument& next) const {
  for (const BlockSpec& b : next.spec.blocks) {
    const BlockSpec* old = previous.findBlock(b.name);
    if (!old) return true;
    auto settings = [](const BlockSpec& spec) {
      std::map<std::string, std::string> out;
      for (const auto& p : spec.properties) out[p.name] = p.text;
      return out;
    };
    if (settings(b) == settings(*old)) continue;
    const int n = net().findNode(b.name);
    if (n < 0) return true;
    const Block& instance = *net().node(n).block;
    // A sub-net is loaded when its block is configured: a new property value needs a new build.
    if (instance.subNet()) return true;
    // So does a property that decides the block's ports (e.g. a number of inputs).
    auto fresh = BlockRegistry::instance().create(b.type);
    try {
      for (const auto& p : b.properties) {
        const PropertySpec* spec = fresh->findProperty(p.name);
        if (!spec) return false;  // setProperty names it
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

void LiveNet::install(const NetDocument& previous, const NetDocument& next) {
  if (structureOf(previous.spec) != structureOf(next.spec) || configurationChanged(previous, next)) {
    rebuild(next);
    return;
  }
  // Only properties (or positions) changed: the executor keeps its cache.
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
        setProperty(next, b.name, name, now);
        done.emplace_back(b.name, name);
      }
    }
  } catch (...) {
    for (const auto& [block, name] : done) setProperty(previous, block, name, findSetting(*previous.findBlock(block), name));
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
