#include "imagenets/executor.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <thread>

#include <imagenets/FeedbackTrace.h>
#include <std_msgs/Float64.h>

#include "feedback_search.h"
#include "imagenets/block_invocation.h"
#include "imagenets/registry.h"
#include "thread_pool.h"

namespace imagenets {

Executor::Executor(std::unique_ptr<Net> net, ExecutorOptions options)
    : net_(std::move(net)), cpu_time_(options.cpu_time) {
  const size_t n = net_->nodes().size();
  int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  // The thread that calls run() works too (it helps while it waits): N threads = N - 1 workers.
  pool_ = std::make_unique<ThreadPool>(std::max(1, threads) - 1);
  outputs_.resize(n);
  external_inputs_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    outputs_[i].resize(net_->node(i).block->outputs().size());
    external_inputs_[i].resize(net_->node(i).block->inputs().size());
  }
  out_of_date_.assign(n, true);
  unfinished_.assign(n, 0);
  stats_.resize(n);

  // Feedback regions: the tuned block and every block on a path from it to the score block.
  feedback_region_.resize(n);
  absorbed_by_.assign(n, -1);
  std::vector<std::string> errors;
  for (size_t i = 0; i < n; ++i) {
    const auto& fb = net_->node(i).feedback;
    if (!fb) continue;
    const int score = net_->findNode(fb->score_block);
    std::vector<int> region{static_cast<int>(i)};
    for (int d : net_->descendants(static_cast<int>(i))) {
      auto below = net_->descendants(d);
      if (d == score || std::find(below.begin(), below.end(), score) != below.end()) region.push_back(d);
    }
    for (int m : region) {
      if (m != static_cast<int>(i) && net_->node(m).feedback) {
        errors.push_back(fb->loc.str() + ": block '" + net_->node(i).name + "': feedback: block '" +
                         net_->node(m).name + "' between it and its score has feedback too; nest one of "
                         "them in a sub-net instead");
      }
      if (m != static_cast<int>(i) && absorbed_by_[m] >= 0) {
        errors.push_back(fb->loc.str() + ": block '" + net_->node(i).name + "': feedback: block '" +
                         net_->node(m).name + "' already lies in the feedback region of '" +
                         net_->node(absorbed_by_[m]).name + "'");
      }
      if (m != static_cast<int>(i)) absorbed_by_[m] = static_cast<int>(i);
    }
    feedback_region_[i] = region;
  }
  if (!errors.empty()) throw NetError(errors);
  trial_schedule_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (net_->node(i).feedback) trial_schedule_[i] = plan(feedback_region_[i], true);
  }
}

std::unique_ptr<Executor> Executor::loadFile(const std::string& path, ExecutorOptions options) {
  return std::make_unique<Executor>(Net::loadFile(path), options);
}

Executor::~Executor() = default;

int Executor::threads() const { return pool_->size() + 1; }

void Executor::markOutOfDate(int node) {
  // A block inside a feedback region changes the scores: the whole sweep must run again.
  if (absorbed_by_[node] >= 0) node = absorbed_by_[node];
  out_of_date_[node] = true;
  for (int d : net_->descendants(node)) out_of_date_[d] = true;
}

RunReport Executor::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  RunReport report = runOutOfDate();
  lock.unlock();
  return finishRun(std::move(report));
}

RunReport Executor::runBlock(const std::string& block) {
  std::unique_lock<std::mutex> lock(mutex_);
  markOutOfDate(nodeIndex(block));
  RunReport report = runOutOfDate();
  lock.unlock();
  return finishRun(std::move(report));
}

RunReport Executor::runBlockOnly(const std::string& block) {
  std::unique_lock<std::mutex> lock(mutex_);
  const int n = nodeIndex(block);
  beginRun();
  RunReport report;
  execute(plan({n}, false), outputs_, report, nullptr);
  // What ran is up to date unless cancelled or it read inputs that an out-of-date block above it
  // will change on the next run; what reads its new outputs is not.
  std::vector<int> ran{n};
  if (net_->node(n).feedback) ran = feedback_region_[n];
  std::vector<bool> stale_above(out_of_date_.size(), false);
  for (int k = 0; k < static_cast<int>(out_of_date_.size()); ++k) {
    if (!out_of_date_[k] || std::find(ran.begin(), ran.end(), k) != ran.end()) continue;
    for (int d : net_->descendants(k)) stale_above[d] = true;
  }
  for (int d : net_->descendants(n)) out_of_date_[d] = true;
  for (int m : ran) out_of_date_[m] = unfinished_[m] != 0 || stale_above[m];
  report.cancelled = anyUnfinished();
  lock.unlock();
  return finishRun(std::move(report));
}

RunReport Executor::runAll() {
  std::unique_lock<std::mutex> lock(mutex_);
  out_of_date_.assign(out_of_date_.size(), true);
  RunReport report = runOutOfDate();
  lock.unlock();
  return finishRun(std::move(report));
}

void Executor::beginRun() {
  cancel_ = false;
  running_ = true;
  unfinished_.assign(unfinished_.size(), 0);
}

bool Executor::anyUnfinished() const {
  return std::find(unfinished_.begin(), unfinished_.end(), 1) != unfinished_.end();
}

RunReport Executor::runOutOfDate() {
  beginRun();
  std::vector<int> nodes;
  for (int n : net_->topologicalOrder()) {
    if (out_of_date_[n]) {
      nodes.push_back(n);
    } else if (watched()) {
      emitBlockEvent(RunEventKind::BlockCached, n, statsOf(n));
    }
  }
  RunReport report;
  if (nodes != scheduled_nodes_ || run_schedule_.providers.empty()) {
    run_schedule_ = plan(nodes, false);
    scheduled_nodes_ = nodes;
  }
  execute(run_schedule_, outputs_, report, nullptr);
  // A cancelled block keeps its previous outputs but stays out of date: the next run resumes.
  for (int n : nodes) out_of_date_[n] = unfinished_[n] != 0;
  report.cancelled = anyUnfinished();
  return report;
}

RunReport Executor::finishRun(RunReport report) {
  running_ = false;
  cancel_ = false;
  RunEvent event;
  event.kind = RunEventKind::RunFinished;
  event.message = report.cancelled ? "cancelled" : "";
  emit(event);
  return report;
}

int Executor::addObserver(RunObserver observer) {
  std::lock_guard<std::mutex> lock(observers_mutex_);
  observers_[next_observer_] = std::move(observer);
  observer_count_ = static_cast<int>(observers_.size());
  return next_observer_++;
}

void Executor::removeObserver(int id) {
  std::lock_guard<std::mutex> lock(observers_mutex_);
  observers_.erase(id);
  observer_count_ = static_cast<int>(observers_.size());
}

void Executor::cancel() {
  if (running_) cancel_ = true;
}

void Executor::nestIn(RunChannel outer) {
  std::lock_guard<std::mutex> lock(mutex_);
  outer_ = std::move(outer);
}

bool Executor::cancelled() const { return cancel_ || (outer_.cancelled && outer_.cancelled()); }

bool Executor::watched() const { return observer_count_ > 0 || outer_.emit; }

void Executor::emit(const RunEvent& event) {
  if (!watched()) return;
  std::vector<RunObserver> observers;
  {
    std::lock_guard<std::mutex> lock(observers_mutex_);
    for (const auto& kv : observers_) observers.push_back(kv.second);
  }
  for (const auto& observer : observers) observer(event);
  // The outer run reports its own end; the inner run's end shows as the block finishing.
  if (outer_.emit && event.kind != RunEventKind::RunFinished) outer_.emit(event);
}

void Executor::emitBlockEvent(RunEventKind kind, int node, const BlockStats& stats) {
  if (!watched()) return;
  RunEvent event;
  event.kind = kind;
  event.block = net_->node(node).name;
  event.stats = stats;
  emit(event);
}

void Executor::setInput(const std::string& block_port, const Value& value) {
  std::lock_guard<std::mutex> lock(mutex_);
  Endpoint in = net_->resolveInput(block_port);
  const Net::Node& node = net_->node(in.node);
  const PortSpec& port = node.block->inputs()[in.port];
  if (node.input_links[in.port].valid()) {
    throw NetError({net_->origin() + ": input " + block_port + " is fed by a link; set an unlinked input"});
  }
  if (value && value.type->name != port.type->name) {
    throw NetError({net_->origin() + ": input " + block_port + " is " + port.type->name + ", not " + value.type->name});
  }
  external_inputs_[in.node][in.port] = value;
  markOutOfDate(in.node);
}

int Executor::nodeIndex(const std::string& block) const {
  const int n = net_->findNode(block);
  if (n < 0) throw NetError({net_->origin() + ": no block named '" + block + "'"});
  return n;
}

std::unique_ptr<Block> Executor::reconfigured(int node, const PropertyValues& changes) const {
  const Net::Node& n = net_->node(node);
  if (!n.block->info()) throw std::logic_error("block '" + n.name + "' was not made by the registry");
  std::unique_ptr<Block> fresh = n.block->info()->create();
  fresh->setInfo(n.block->info());
  if (n.feedback) {
    const PortSpec& trace = *n.block->findOutput("feedback_trace");
    fresh->attachOutput(trace.name, *trace.type, trace.doc);
  }
  // configure() sees the net it is part of, as when the net was built (a sub-net's includes).
  NetSpec context;
  context.origin = net_->origin();
  context.base_dir = net_->baseDir();
  context.include_chain = net_->includeChain();
  LoadContext::Scope scope(context);
  try {
    configureLike(*fresh, *n.block, changes);
  } catch (const NetError& e) {
    std::vector<std::string> errors;
    for (const auto& inner : e.errors()) errors.push_back(net_->origin() + ": block '" + n.name + "': " + inner);
    throw NetError(errors);
  } catch (const std::exception& e) {
    throw NetError({net_->origin() + ": block '" + n.name + "': " + e.what()});
  }
  return fresh;
}

Executor::PropertyChange Executor::setProperties(const std::string& block, const PropertyValues& values) {
  std::lock_guard<std::mutex> lock(mutex_);
  const int n = nodeIndex(block);
  Net::Node& node = net_->node(n);
  bool changed = false;
  for (const auto& [name, value] : values) {
    try {
      const PropertyValue valid = node.block->propertySpec(name).validate(value);
      changed = changed || valid != node.block->propertyValue(name);
    } catch (const PropertyError& e) {
      const std::string why = node.block->findProperty(name) ? "property '" + name + "': " + e.what() : e.what();
      throw NetError({net_->origin() + ": block '" + block + "': " + why});
    }
  }
  if (changed) {
    std::unique_ptr<Block> fresh = reconfigured(n, values);
    if (!samePorts(*fresh, *node.block)) return PropertyChange::NeedsRebuild;
    node.block = std::move(fresh);
  }
  markOutOfDate(n);
  return PropertyChange::Applied;
}

void Executor::setProperty(const std::string& block, const std::string& property, const PropertyValue& value) {
  if (setProperties(block, {{property, value}}) == PropertyChange::NeedsRebuild) {
    throw NetError({net_->origin() + ": block '" + block + "': property '" + property + "': " + toString(value) +
                    " changes the block's ports; build the net anew with it"});
  }
}

void Executor::markOutOfDate(const std::string& block) {
  std::lock_guard<std::mutex> lock(mutex_);
  markOutOfDate(nodeIndex(block));
}

void Executor::setPropertyText(const std::string& block, const std::string& property, const std::string& text) {
  PropertyValue v;
  try {
    v = net_->node(nodeIndex(block)).block->parseProperty(property, text);  // relative: the working directory
  } catch (const PropertyError& e) {
    throw NetError({net_->origin() + ": block '" + block + "': " + e.what()});
  }
  setProperty(block, property, v);
}

Value Executor::output(const std::string& block_port) const {
  std::lock_guard<std::mutex> lock(mutex_);
  Endpoint out = net_->resolveOutput(block_port);
  return outputs_[out.node][out.port];
}

BlockStats Executor::stats(const std::string& block) const { return statsOf(nodeIndex(block));
}

BlockStats Executor::statsOf(int node) const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_[node];
}

void Executor::record(int node, BlockStatus status, const std::string& message, double ms, bool counted,
                      double cpu_ms) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  stats_[node].record(status, message, ms, counted, cpu_ms);
}

void Executor::finish(int node, BlockStatus status, const std::string& message, double ms, bool counted,
                      double cpu_ms) {
  record(node, status, message, ms, counted, cpu_ms);
  if (watched()) emitBlockEvent(RunEventKind::BlockFinished, node, statsOf(node));
}

void Executor::skipCancelled(int unit, RunReport& report) {
  std::vector<int> members = net_->node(unit).feedback ? feedback_region_[unit] : std::vector<int>{unit};
  for (int m : members) {
    unfinished_[m] = 1;
    finish(m, BlockStatus::NotRun, "cancelled", 0.0, false);
    std::lock_guard<std::mutex> lock(report_mutex_);
    report.not_run.push_back(net_->node(m).name + ": cancelled");
  }
}

std::vector<Value> Executor::gatherInputs(int node, const Store& store) const {
  const Net::Node& n = net_->node(node);
  std::vector<Value> values(n.input_links.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const Endpoint& link = n.input_links[i];
    values[i] = link.valid() ? store[link.node][link.port] : external_inputs_[node][i];
  }
  return values;
}

std::string Executor::explainMissing(int node, int input) const {
  const Net::Node& n = net_->node(node);
  const Endpoint& link = n.input_links[input];
  return "input '" + n.block->inputs()[input].name + "' has no value" +
         (link.valid() ? " (block '" + net_->node(link.node).name + "' produced none)" : " (not linked, not set)");
}

void Executor::runNode(int node, Store& store, RunReport& report, const Overrides* overrides) {
  Net::Node& n = net_->node(node);
  const bool trial = overrides != nullptr;  // a feedback trial reports through FeedbackTrial events only
  std::shared_ptr<const PropertyValues> properties = n.block->propertySnapshot();
  if (overrides) {
    auto it = overrides->find(node);
    if (it != overrides->end()) {
      auto changed = std::make_shared<PropertyValues>(*properties);
      for (const auto& kv : it->second) (*changed)[kv.first] = kv.second;
      properties = std::move(changed);
    }
  }
  // What nobody watches is not built: no events, no CPU clock (unless asked for).
  InvocationOptions options;
  options.channel = RunChannel{trial ? RunObserver() : [this](const RunEvent& e) { emit(e); }, [this] { return cancelled(); }};
  const bool shown = watched();
  if (!trial && shown) options.starting = [this, node] { emitBlockEvent(RunEventKind::BlockStarted, node, statsOf(node)); };
  options.cpu_time = cpu_time_ || shown;
  BlockInvocation run = invokeBlock(*n.block, n.name, gatherInputs(node, store), std::move(properties), std::move(options));
  if (run.cancelled) {
    // Stopped early on cancel: previous outputs kept, out of date (a trial simply gives no score).
    if (!trial) skipCancelled(node, report);
    return;
  }
  std::string message = run.missing_input >= 0 ? explainMissing(node, run.missing_input) : run.message;
  if (trial) record(node, run.status, message, run.ms, run.processed, run.cpu_ms);
  else finish(node, run.status, message, run.ms, run.processed, run.cpu_ms);
  store[node] = std::move(run.outputs);
  std::lock_guard<std::mutex> lock(report_mutex_);
  if (run.status == BlockStatus::Ok) report.ran.push_back(n.name);
  else if (run.status == BlockStatus::Failed) report.failed.push_back(message);
  else report.not_run.push_back(n.name + ": " + message);
}

Executor::Schedule Executor::plan(const std::vector<int>& nodes, bool trial) const {
  const size_t count = net_->nodes().size();
  std::vector<char> in_set(count, 0);
  for (int n : nodes) in_set[n] = 1;
  // Outside trials, a feedback node stands for its whole region: the region runs as one unit.
  auto unitOf = [&](int n) { return !trial && absorbed_by_[n] >= 0 && in_set[absorbed_by_[n]] ? absorbed_by_[n] : n; };

  Schedule schedule;
  schedule.providers.assign(count, 0);
  schedule.dependents.resize(count);
  std::vector<std::set<int>> providers(count);
  for (int n : nodes) {
    const int u = unitOf(n);
    if (u == n) schedule.units.push_back(n);
    std::vector<int> feeding;
    for (const Endpoint& link : net_->node(n).input_links) {
      if (link.valid()) feeding.push_back(link.node);
    }
    // A feedback sweep also waits for the blocks its initial candidates come from.
    if (!trial && net_->node(n).feedback) {
      for (const FeedbackInitial& init : net_->node(n).feedback->initial) {
        if (init.fromPort()) feeding.push_back(net_->findNode(init.block));
      }
    }
    for (int p : feeding) {
      if (!in_set[p]) continue;
      const int pu = unitOf(p);
      if (pu != u && providers[u].insert(pu).second) schedule.dependents[pu].push_back(u);
    }
  }
  for (int u : schedule.units) schedule.providers[u] = providers[u].size();
  return schedule;
}

void Executor::runUnit(int unit, Store& store, RunReport& report, const Overrides* overrides) {
  const bool trial = overrides != nullptr;  // inside a trial, a feedback node runs as a plain block
  // After a cancel nothing starts: the rest of the set is skipped (a trial's blocks silently).
  if (cancelled()) {
    if (!trial) skipCancelled(unit, report);
  } else if (!trial && net_->node(unit).feedback) {
    runFeedback(unit, store, report);
  } else {
    runNode(unit, store, report, overrides);
  }
}

void Executor::execute(const Schedule& schedule, Store& store, RunReport& report, const Overrides* overrides) {
  if (schedule.units.empty()) return;
  std::vector<size_t> waiting = schedule.providers;
  std::mutex schedule_mutex;
  size_t remaining = schedule.units.size();
  // Whoever finishes a unit goes on with one unit it made ready (a chain stays on its thread, with
  // no hand-over) and posts the others at once: a unit that blocks its thread (a sub-net waiting
  // for its twin, a camera) must not hold back the rest of the net.
  std::function<void(int)> runFrom = [&](int unit) {
    for (int u = unit; u >= 0;) {
      runUnit(u, store, report, overrides);
      int next = -1;
      std::vector<int> others;
      {
        std::lock_guard<std::mutex> lock(schedule_mutex);
        --remaining;
        for (int d : schedule.dependents[u]) {
          if (--waiting[d] != 0) continue;
          if (next < 0) next = d;
          else others.push_back(d);
        }
      }
      for (int d : others) pool_->post([&runFrom, d] { runFrom(d); });
      u = next;
    }
  };
  std::vector<int> first;  // collected before any starts: running units change `waiting`
  for (int u : schedule.units) {
    if (waiting[u] == 0) first.push_back(u);
  }
  for (int u : first) pool_->post([&runFrom, u] { runFrom(u); });
  pool_->helpUntil([&] {
    std::lock_guard<std::mutex> lock(schedule_mutex);
    return remaining == 0;
  });
}

double Executor::runTrial(int node, double candidate, const Store& base, Store& trial_store) {
  const Net::Node& n = net_->node(node);
  const FeedbackSpec& f = *n.feedback;
  Overrides overrides;
  try {
    overrides[node][f.property] = n.block->findProperty(f.property)->fromNumber(candidate);
  } catch (const PropertyError&) {
    return std::numeric_limits<double>::quiet_NaN();  // e.g. an initial value out of the property's range
  }
  // Only what the region reads: its providers' outputs, which are final while it runs (other
  // blocks may be writing their own entries of `base` concurrently).
  trial_store.assign(base.size(), {});
  for (int m : feedback_region_[node]) {
    for (const Endpoint& link : net_->node(m).input_links) {
      if (link.valid()) trial_store[link.node] = base[link.node];
    }
  }
  for (int m : feedback_region_[node]) trial_store[m].assign(net_->node(m).block->outputs().size(), Value());
  RunReport trial_report;
  execute(trial_schedule_[node], trial_store, trial_report, &overrides);
  const Endpoint score = net_->resolveOutput(f.score_block + "." + f.score_port);
  auto value = trial_store[score.node][score.port].as<std_msgs::Float64>();
  return value && std::isfinite(value->data) ? value->data : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> Executor::initialCandidates(int node, const Store& store) const {
  std::vector<double> values;
  for (const FeedbackInitial& init : net_->node(node).feedback->initial) {
    if (!init.fromPort()) {
      values.push_back(init.value);
      continue;
    }
    // A providing block that failed adds no candidate; the search goes on without it.
    const Endpoint from = net_->resolveOutput(init.block + "." + init.port);
    if (auto v = store[from.node][from.port].as<std_msgs::Float64>()) values.push_back(v->data);
  }
  return values;
}

void Executor::runFeedback(int node, Store& store, RunReport& report) {
  const Net::Node& n = net_->node(node);
  const int missing_input = missingInput(*n.block, gatherInputs(node, store));
  if (missing_input >= 0) return skipFeedbackRegion(node, explainMissing(node, missing_input), store, report);
  // The search (feedback_search.h) decides which candidates to try; here they only run.
  const PropertySpec* property = n.block->findProperty(n.feedback->property);
  FeedbackSearch search(*n.feedback, initialCandidates(node, store), [property](double v) {
    try {
      return toNumber(property->fromNumber(v));
    } catch (const PropertyError&) {
      return v;  // out of range: its trial fails and counts as invalid
    }
  });
  if (watched()) {
    for (int m : feedback_region_[node]) emitBlockEvent(RunEventKind::BlockStarted, m, statsOf(m));
  }
  Store best_store = sweep(node, search, store);
  if (cancelled()) return skipCancelled(node, report);
  keepBestTrial(node, search, std::move(best_store), store, report);
}

void Executor::skipFeedbackRegion(int node, const std::string& missing, Store& store, RunReport& report) {
  for (int m : feedback_region_[node]) {
    store[m].assign(net_->node(m).block->outputs().size(), Value());
    finish(m, BlockStatus::NotRun, m == node ? missing : "block '" + net_->node(node).name + "' did not run", 0.0, false);
  }
  std::lock_guard<std::mutex> lock(report_mutex_);
  report.not_run.push_back(net_->node(node).name + ": " + missing);
}

Executor::Store Executor::sweep(int node, FeedbackSearch& search, const Store& store) {
  // A batch runs in chunks, each chunk's trials in parallel, and the scores go back in batch
  // order, so a sequential search (chunks of one) tries exactly the same candidates and keeps the
  // same best.
  const size_t chunk_size = net_->node(node).feedback->parallel ? static_cast<size_t>(2 * threads()) : 1;
  Store best_store;
  for (auto batch = search.nextBatch(); !batch.empty() && !cancelled(); batch = search.nextBatch()) {
    for (size_t first = 0; first < batch.size() && !search.finished(); first += chunk_size) {
      const size_t count = std::min(chunk_size, batch.size() - first);
      std::vector<double> scores(count);
      std::vector<Store> stores(count);
      runParallel(count, [&](size_t k) {
        if (!cancelled()) scores[k] = runTrial(node, batch[first + k], store, stores[k]);
      });
      for (size_t k = 0; k < count; ++k) {
        // A trial cut short or skipped by a cancel does not count; the search stops.
        if (cancelled()) {
          search.cancel();
          break;
        }
        const bool more = search.report(scores[k]);
        if (search.best() == static_cast<int>(search.trials().size()) - 1) best_store = std::move(stores[k]);
        emitTrial(node, search);
        if (!more) break;
      }
    }
  }
  return best_store;
}

void Executor::emitTrial(int node, const FeedbackSearch& search) {
  const auto& trial = search.trials().back();
  RunEvent event;
  event.kind = RunEventKind::FeedbackTrial;
  event.block = net_->node(node).name;
  event.message = net_->node(node).feedback->property;
  event.value = trial.value;
  event.score = trial.score;
  event.index = static_cast<int>(search.trials().size());
  event.count = static_cast<int>(search.candidates());
  emit(event);
}

Value Executor::feedbackTrace(int node, const FeedbackSearch& search) const {
  // Every (value, score) in the order tried, why the search stopped, the chosen value.
  const FeedbackSpec& f = *net_->node(node).feedback;
  const int best = search.best();
  auto trace = boost::make_shared<FeedbackTrace>();
  trace->block = net_->node(node).name;
  trace->property = f.property;
  trace->score = f.score_block + "." + f.score_port;
  trace->maximize = f.maximize;
  trace->candidates = search.candidates();
  trace->trials = search.trials().size();
  for (const auto& t : search.trials()) {
    trace->values.push_back(t.value);
    trace->scores.push_back(t.score);
  }
  trace->stop_reason = FeedbackSearch::stopName(search.stop());
  trace->found = best >= 0;
  trace->chosen_value = best >= 0 ? search.trials()[best].value : std::numeric_limits<double>::quiet_NaN();
  trace->chosen_score = best >= 0 ? search.trials()[best].score : std::numeric_limits<double>::quiet_NaN();
  return PortType::of<FeedbackTrace>().wrap<FeedbackTrace>(trace);
}

void Executor::keepBestTrial(int node, const FeedbackSearch& search, Store best_store, Store& store, RunReport& report) {
  const Net::Node& n = net_->node(node);
  const auto& region = feedback_region_[node];
  const int trace_port = n.block->outputIndex("feedback_trace");
  if (search.best() < 0) {
    // No valid candidate: the region produces nothing, so downstream blocks do not run; the
    // trace still goes out so a plot shows what was tried.
    const std::string message = "block '" + n.name + "': feedback: no valid candidate: no value of '" +
                                n.feedback->property + "' produced a score at " + n.feedback->score_block + "." +
                                n.feedback->score_port;
    for (int m : region) store[m].assign(net_->node(m).block->outputs().size(), Value());
    store[node][trace_port] = feedbackTrace(node, search);
    finish(node, BlockStatus::Failed, message, 0.0, false);
    for (int m : region) {
      if (m != node) finish(m, BlockStatus::NotRun, "feedback of '" + n.name + "' found no valid candidate", 0.0, false);
    }
    std::lock_guard<std::mutex> lock(report_mutex_);
    report.failed.push_back(message);
    return;
  }
  for (int m : region) store[m] = best_store[m];
  store[node][trace_port] = feedbackTrace(node, search);
  for (int m : region) finish(m, BlockStatus::Ok, "", 0.0, false);
  std::lock_guard<std::mutex> lock(report_mutex_);
  for (int m : region) report.ran.push_back(net_->node(m).name);
}

void Executor::runParallel(size_t count, const std::function<void(size_t)>& task) {
  if (count == 1) return task(0);
  std::mutex m;
  size_t finished = 0;
  for (size_t k = 0; k < count; ++k) {
    pool_->post([&, k] {
      task(k);
      std::lock_guard<std::mutex> lock(m);
      ++finished;
    });
  }
  pool_->helpUntil([&] {
    std::lock_guard<std::mutex> lock(m);
    return finished == count;
  });
}

}  // namespace imagenets
