#include "imagenets/blocks/sub_net_block.h"

#include <boost/filesystem.hpp>
#include <std_msgs/Bool.h>
#include <std_msgs/Int32.h>
#include <std_msgs/String.h>

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
  addProperty<std::string>("repetition_input", "",
                           "inner input port (std_msgs/Int32) fed with the repetition's index 0..N-1 (not an outer port)");
  addProperty<bool>("repeat_from_input", false, "the number of repetitions comes from the input `repeat` (std_msgs/Int32)");
  addProperty<std::string>("until_net", "",
                           "a net run after repetition N and each one added: its std_msgs/Bool output `done` ends "
                           "the repetitions (inputs: this block's inputs and the collections `<port>_all` so far)")
      .path();
  addProperty<int>("max_repeat", 0, "with `until_net`: at most this many repetitions (0 = N; the input `max_repeat` "
                                    "when it has a value)")
      .range(0, 100000);
}

SubNetBlock::~SubNetBlock() = default;

namespace {

// The nets including the one being built, outermost first, and that one: a sub-net may not be
// among them.
std::vector<std::string> includeChain() {
  const NetSpec* outer = LoadContext::current();
  std::vector<std::string> chain = outer ? outer->include_chain : std::vector<std::string>{};
  if (outer) chain.push_back(outer->origin);
  return chain;
}

NetSpec parseIncluded(const std::string& path, const std::vector<std::string>& chain) {
  for (const auto& including : chain) {
    if (canonical(including) != canonical(path)) continue;
    std::string loop;
    for (const auto& c : chain) loop += c + " -> ";
    throw BlockError("net '" + path + "' includes itself: " + loop + path);
  }
  NetSpec included = parseNetFile(path);
  included.include_chain = chain;
  return included;
}

}  // namespace

void SubNetBlock::configure() {
  const std::string file = property<std::string>("net");
  const std::string yaml = property<std::string>("net_yaml");
  if (file.empty() == yaml.empty()) throw BlockError("set exactly one of the properties 'net' (a file) and 'net_yaml'");
  const std::vector<std::string> chain = includeChain();
  NetSpec spec;
  if (!file.empty()) {
    spec = parseIncluded(file, chain);
  } else {
    const NetSpec* outer = LoadContext::current();
    spec = parseNetText(yaml, (outer ? outer->origin : std::string("net")) + " (net_yaml)",
                        outer ? outer->base_dir : std::string());
  }
  spec.include_chain = chain;
  executor_ = std::make_unique<Executor>(Net::build(spec), ExecutorOptions{property<int>("threads")});
  if (property<bool>("repeat_from_input")) {
    addInput<std_msgs::Int32>("repeat", "number of repetitions of this run (>= 1; instead of the property `repeat`)");
  }
  declarePorts(spec.origin);
  if (property<int>("max_failures") > 0) {
    addOutput<std_msgs::String>("failure", "why the first failed repetition failed; only when one failed");
  }
  configureUntil(chain);
}

void SubNetBlock::declarePorts(const std::string& origin) {
  const Net& net = executor_->net();
  const std::string repetition_port = property<std::string>("repetition_input");
  repetition_input_.clear();
  if (!repetition_port.empty()) {
    const int node = findNetPort(net, NetPort::Direction::In, repetition_port);
    if (node < 0) {
      throw BlockError("property 'repetition_input': " + origin + " has no input port '" + repetition_port +
                       "' (an imagenets/SubNetInput with port '" + repetition_port + "', type std_msgs/Int32)");
    }
    const PortType& type = netPortAt(net, node).type();
    if (type.name != PortType::of<std_msgs::Int32>().name) {
      throw BlockError("property 'repetition_input': port '" + repetition_port + "' of " + origin + " is " + type.name +
                       ", expected std_msgs/Int32");
    }
    repetition_input_ = net.node(node).name + ".value";
  }
  for (const std::string& port : netPortNames(net, NetPort::Direction::In)) {
    if (port == repetition_port) continue;  // fed the repetition's index, not an outer port
    const int node = findNetPort(net, NetPort::Direction::In, port);
    const NetPort& boundary = netPortAt(net, node);
    const std::string& block = net.node(node).name;
    addInput(port, boundary.type(), "sub-net input '" + block + "'").optional = boundary.optional();
    inputs_.push_back({port, block + ".value"});
  }
  for (const std::string& port : netPortNames(net, NetPort::Direction::Out)) {
    const int node = findNetPort(net, NetPort::Direction::Out, port);
    const PortType& type = netPortAt(net, node).type();
    const std::string& block = net.node(node).name;
    addOutput(port, type, "sub-net output '" + block + "' (last repetition)");
    const Collector* collector = Collectors::find(type);
    outputs_.push_back({port, block + ".value", collector});
    if (collector) addOutput(port + "_all", *collector->collection, "the results of all repetitions of '" + port + "'");
  }
}

void SubNetBlock::configureUntil(const std::vector<std::string>& chain) {
  // Repeat until: the until net's ports are matched by name against this block's ports.
  until_.reset();
  until_inputs_.clear();
  const std::string until_file = property<std::string>("until_net");
  if (until_file.empty()) return;
  const NetSpec until_spec = parseIncluded(until_file, chain);
  until_ = std::make_unique<Executor>(Net::build(until_spec), ExecutorOptions{property<int>("threads")});
  if (property<bool>("repeat_from_input")) {
    addOptionalInput<std_msgs::Int32>("max_repeat", "at most this many repetitions (instead of the property)");
  }
  until_done_.clear();
  const Net& net = until_->net();
  for (const std::string& port : netPortNames(net, NetPort::Direction::In)) {
    const int node = findNetPort(net, NetPort::Direction::In, port);
    until_inputs_.push_back(untilInput(net.node(node).name, port, netPortAt(net, node).type(), until_spec.origin));
  }
  const int done = findNetPort(net, NetPort::Direction::Out, "done");
  if (done < 0) {
    throw BlockError("property 'until_net': " + until_spec.origin +
                     " has no output 'done' (an imagenets/SubNetOutput with port 'done', type std_msgs/Bool)");
  }
  const PortType& type = netPortAt(net, done).type();
  if (type.name != PortType::of<std_msgs::Bool>().name) {
    throw BlockError("property 'until_net': output 'done' of " + until_spec.origin + " is " + type.name +
                     ", expected std_msgs/Bool");
  }
  until_done_ = net.node(done).name + ".value";
}

SubNetBlock::UntilInPort SubNetBlock::untilInput(const std::string& block, const std::string& port,
                                                 const PortType& type, const std::string& origin) const {
  UntilInPort in{block + ".value"};
  std::string offered;
  for (size_t i = 0; i < inputs_.size(); ++i) {
    if (inputs_[i].port == port) in.input = static_cast<int>(i);
    offered += (offered.empty() ? "" : ", ") + inputs_[i].port;
  }
  for (size_t o = 0; o < outputs_.size(); ++o) {
    if (!outputs_[o].collector) continue;
    if (outputs_[o].port + "_all" == port) in.output = static_cast<int>(o);
    offered += (offered.empty() ? "" : ", ") + outputs_[o].port + "_all";
  }
  if (in.input < 0 && in.output < 0) {
    throw BlockError("property 'until_net': input '" + port + "' of " + origin +
                     " is neither an input of this block nor a collection of its outputs (have: " + offered + ")");
  }
  const PortType& fed = in.input >= 0 ? *findInput(port)->type : *outputs_[in.output].collector->collection;
  if (fed.name != type.name) {
    throw BlockError("property 'until_net': input '" + port + "' of " + origin + " is " + type.name +
                     ", but this block's '" + port + "' is " + fed.name);
  }
  return in;
}

bool SubNetBlock::untilDone(const std::vector<std::vector<Value>>& results, const std::vector<Value>& inputs,
                            std::string* verdict) {
  for (const auto& in : until_inputs_) {
    if (in.input >= 0) {
      until_->setInput(in.inner, inputs[in.input]);
    } else if (!results[in.output].empty()) {
      until_->setInput(in.inner, outputs_[in.output].collector->collect(results[in.output]));
    } else {
      *verdict = "until net not asked: no repetition has succeeded yet";
      return false;
    }
  }
  // A failed run is not done: more repetitions may well help.
  const RunReport report = until_->run();
  if (report.cancelled) throw RunCancelled();
  if (!report.failed.empty()) {
    *verdict = "until net failed: " + report.failed.front();
    return false;
  }
  const auto done = until_->output<std_msgs::Bool>(until_done_);
  *verdict = done && done->data ? "until net: done" : "until net: not done";
  return done && done->data;
}

int SubNetBlock::repetitions(Context& ctx) const {
  if (!ctx.property<bool>("repeat_from_input")) return ctx.property<int>("repeat");
  const int repeat = ctx.input<std_msgs::Int32>("repeat")->data;
  if (repeat < 1) throw BlockError("input 'repeat': " + std::to_string(repeat) + " repetitions (must be >= 1)");
  return repeat;
}

int SubNetBlock::maxRepetitions(Context& ctx, int repeat) const {
  // Repeat until: past the N repetitions, one more at a time while the until net is not done.
  if (!until_) return repeat;
  const auto from_input = ctx.property<bool>("repeat_from_input") ? ctx.input<std_msgs::Int32>("max_repeat") : nullptr;
  const int limit = from_input ? from_input->data : ctx.property<int>("max_repeat");
  const int max_repeat = limit != 0 || from_input ? limit : repeat;
  if (max_repeat < repeat) {
    throw BlockError(std::string(from_input ? "input" : "property") + " 'max_repeat': " + std::to_string(max_repeat) +
                     " is below the " + std::to_string(repeat) + " repetitions that run anyway");
  }
  return max_repeat;
}

bool SubNetBlock::repeatOnce(int i, int repeat, int max_repeat, Context& ctx, const std::vector<Value>& inputs,
                             Repetitions& r) {
  if (ctx.cancelled()) throw RunCancelled();
  if (!repetition_input_.empty()) {
    auto index = boost::make_shared<std_msgs::Int32>();
    index->data = i;
    executor_->setInput(repetition_input_, PortType::of<std_msgs::Int32>().wrap<std_msgs::Int32>(index));
  }
  // Every repetition re-runs the whole sub-net (sources included: a fresh image, a new move).
  RunReport report = max_repeat == 1 ? executor_->run() : executor_->runAll();
  if (report.cancelled) throw RunCancelled();
  ++r.ran;
  RunEvent done;
  done.kind = RunEventKind::Repetition;
  done.index = i + 1;
  done.count = max_repeat;
  done.stats.status = report.failed.empty() ? BlockStatus::Ok : BlockStatus::Failed;
  if (!report.failed.empty()) {
    done.stats.message = report.failed.front();
    done.message = "failed: " + report.failed.front();
    // Its outputs may still hold the previous repetition's values: none of them is taken.
    if (++r.failures == 1) {
      r.first_failure = "repetition " + std::to_string(i + 1) + ": " + report.failed.front();
      r.first_failure_message = report.failed.front();
    }
  } else {
    for (size_t o = 0; o < outputs_.size(); ++o) {
      Value v = executor_->output(outputs_[o].inner);
      if (v) r.results[o].push_back(v);
    }
  }
  // The until net decides from repetition N on whether more are needed (not when none may follow).
  bool enough = i + 1 >= repeat;
  if (enough && i + 1 < max_repeat) {
    Nesting until_nesting(*until_, RunChannel{[&ctx](RunEvent e) {
                                                e.block = "until/" + e.block;
                                                ctx.emit(e);
                                              },
                                              [&ctx] { return ctx.cancelled(); }});
    std::string verdict;
    enough = untilDone(r.results, inputs, &verdict);
    done.message += (done.message.empty() ? "" : "; ") + verdict;
  }
  ctx.emit(done);
  return enough;
}

void SubNetBlock::process(Context& ctx) {
  if (!executor_) throw BlockError("no sub-net loaded");
  // One sub-net instance: concurrent calls (feedback trials) take turns.
  std::lock_guard<std::mutex> lock(run_mutex_);
  Nesting nesting(*executor_, ctx.innerChannel());
  std::vector<Value> input_values;  // also what the until net is fed
  for (const auto& in : inputs_) input_values.push_back(ctx.inputValue(in.port));
  for (size_t i = 0; i < inputs_.size(); ++i) executor_->setInput(inputs_[i].inner, input_values[i]);
  const int repeat = repetitions(ctx);
  const int max_repeat = maxRepetitions(ctx, repeat);
  Repetitions r;
  r.results.resize(outputs_.size());
  for (int i = 0; i < max_repeat; ++i) {
    if (repeatOnce(i, repeat, max_repeat, ctx, input_values, r)) break;
  }
  setOutputs(ctx, r);
}

void SubNetBlock::setOutputs(Context& ctx, const Repetitions& r) const {
  // With max_failures >= the repetitions, even all of them failing leaves the block ok: it then
  // hands out only `failure` (e.g. a detection sub-net whose "not found" is a result downstream).
  const int max_failures = ctx.property<int>("max_failures");
  if (r.failures > max_failures || (r.failures == r.ran && max_failures < r.ran)) {
    throw BlockError("sub-net " + executor_->net().origin() + ": " + std::to_string(r.failures) + " of " +
                     std::to_string(r.ran) + " repetitions failed (max_failures " + std::to_string(max_failures) +
                     "); " + r.first_failure);
  }
  if (r.failures > 0) {
    auto why = boost::make_shared<std_msgs::String>();
    why->data = r.first_failure_message;
    ctx.output("failure", why);
  }
  for (size_t o = 0; o < outputs_.size(); ++o) {
    if (r.results[o].empty()) continue;
    ctx.setOutput(outputs_[o].port, r.results[o].back());
    if (outputs_[o].collector) ctx.setOutput(outputs_[o].port + "_all", outputs_[o].collector->collect(r.results[o]));
  }
}

std::vector<InnerExecutorRef> SubNetBlock::innerExecutors() const {
  std::vector<InnerExecutorRef> nets;
  if (executor_) nets.push_back({"", executor_.get()});
  if (until_) nets.push_back({"until", until_.get()});
  return nets;
}

const Net* SubNetBlock::subNet() const { return executor_ ? &executor_->net() : nullptr; }

}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK_TYPE(imagenets::SubNetBlock, "imagenets/SubNet", "sub-net",
                              "Runs a net file as one block (sub-net), optionally N times");
IMAGENETS_REGISTER_BLOCK_FORMER_NAME("imagenets/Executor", "imagenets/SubNet");
