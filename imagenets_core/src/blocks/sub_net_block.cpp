#include "imagenets/blocks/sub_net_block.h"

#include <boost/filesystem.hpp>

#include "imagenets/collectors.h"
#include "imagenets/executor.h"
#include "imagenets/net_port.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace {

std::string canonical(const std::string& path) {
  return boost::filesystem::weakly_canonical(boost::filesystem::absolute(path)).string();
}

// Nests the inner executor in the current outer run for the length of one process() call: the
// inner run's events reach the outer watchers as "<this block>/<inner block>", and the outer
// cancel stops the inner run.
class Nesting {
 public:
  Nesting(Executor& inner, RunChannel outer) : inner_(inner) { inner_.nestIn(std::move(outer)); }
  ~Nesting() { inner_.nestIn({}); }

 private:
  Executor& inner_;
};

}  // namespace

SubNetBlock::SubNetBlock() {
  addProperty<std::string>("net", "", "net file run as this block (relative to the including net)").path();
  addProperty<std::string>("net_yaml", "", "the sub-net written inline as YAML (instead of `net`)");
  addProperty<int>("repeat", 1, "runs of the sub-net per run; outputs also come as collections `<port>_all`")
      .range(1, 100000);
  addProperty<int>("max_failures", 0, "repetitions that may fail (their results are left out); more fail the block")
      .range(0, 100000);
  addProperty<int>("threads", 0, "worker threads of the sub-net (0 = number of cores)").range(0, 64);
}

SubNetBlock::~SubNetBlock() = default;

void SubNetBlock::configure() {
  const std::string file = property<std::string>("net");
  const std::string yaml = property<std::string>("net_yaml");
  if (file.empty() == yaml.empty()) throw BlockError("set exactly one of the properties 'net' (a file) and 'net_yaml'");

  const NetSpec* outer = LoadContext::current();
  std::vector<std::string> chain = outer ? outer->include_chain : std::vector<std::string>{};
  if (outer) chain.push_back(outer->origin);
  NetSpec spec;
  if (!file.empty()) {
    for (const auto& including : chain) {
      if (canonical(including) != canonical(file)) continue;
      std::string path;
      for (const auto& c : chain) path += c + " -> ";
      throw BlockError("net '" + file + "' includes itself: " + path + file);
    }
    spec = parseNetFile(file);
  } else {
    spec = parseNetText(yaml, (outer ? outer->origin : std::string("net")) + " (net_yaml)",
                        outer ? outer->base_dir : std::string());
  }
  spec.include_chain = chain;
  executor_ = std::make_unique<Executor>(Net::build(spec), ExecutorOptions{property<int>("threads")});

  for (const auto& node : executor_->net().nodes()) {
    const auto* boundary = dynamic_cast<const NetPort*>(node.block.get());
    if (!boundary) continue;
    std::string port = boundary->outerName();
    if (port.empty()) port = node.name;
    const PortType& type = boundary->type();
    if (boundary->direction() == NetPort::Direction::In) {
      addInput(port, type, "sub-net input '" + node.name + "'");
      inputs_.push_back({port, node.name + ".value"});
    } else {
      addOutput(port, type, "sub-net output '" + node.name + "' (last repetition)");
      const Collector* collector = Collectors::find(type);
      outputs_.push_back({port, node.name + ".value", collector});
      if (collector) addOutput(port + "_all", *collector->collection, "the results of all repetitions of '" + port + "'");
    }
  }
}

void SubNetBlock::process(Context& ctx) {
  if (!executor_) throw BlockError("no sub-net loaded");
  // One sub-net instance: concurrent calls (feedback trials) take turns.
  std::lock_guard<std::mutex> lock(run_mutex_);
  Nesting nesting(*executor_, ctx.innerChannel());
  for (const auto& in : inputs_) executor_->setInput(in.inner, ctx.inputValue(in.port));
  const int repeat = ctx.property<int>("repeat");
  std::vector<std::vector<Value>> results(outputs_.size());
  std::string first_failure;
  int failures = 0;
  for (int i = 0; i < repeat; ++i) {
    if (ctx.cancelled()) throw RunCancelled();
    // Every repetition re-runs the whole sub-net (sources included: a fresh image, a new move).
    RunReport report = repeat == 1 ? executor_->run() : executor_->runAll();
    if (report.cancelled) throw RunCancelled();
    RunEvent done;
    done.kind = RunEventKind::Repetition;
    done.index = i + 1;
    done.count = repeat;
    if (!report.failed.empty()) done.message = "failed: " + report.failed.front();
    ctx.emit(done);
    if (!report.failed.empty()) {
      // Its outputs may still hold the previous repetition's values: none of them is taken.
      if (++failures == 1) first_failure = "repetition " + std::to_string(i + 1) + ": " + report.failed.front();
      continue;
    }
    for (size_t o = 0; o < outputs_.size(); ++o) {
      Value v = executor_->output(outputs_[o].inner);
      if (v) results[o].push_back(v);
    }
  }
  if (failures > ctx.property<int>("max_failures") || failures == repeat) {
    throw BlockError("sub-net " + executor_->net().origin() + ": " + std::to_string(failures) + " of " +
                     std::to_string(repeat) + " repetitions failed (max_failures " +
                     std::to_string(ctx.property<int>("max_failures")) + "); " + first_failure);
  }
  for (size_t o = 0; o < outputs_.size(); ++o) {
    if (results[o].empty()) continue;
    ctx.setOutput(outputs_[o].port, results[o].back());
    if (outputs_[o].collector) ctx.setOutput(outputs_[o].port + "_all", outputs_[o].collector->collect(results[o]));
  }
}

const Net* SubNetBlock::subNet() const { return executor_ ? &executor_->net() : nullptr; }

}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::SubNetBlock, "imagenets/Executor", "executor",
                              "Runs a net file as one block (sub-net), optionally N times");
