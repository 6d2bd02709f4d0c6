// The ImageNet Executor block (paper 3.5): runs a net file as one block of another net. The
// sub-net's ExecutorInput / ExecutorOutput blocks become this block's ports. With `repeat: N` the
// sub-net runs N times per run (paper 4.2, Fig. 4.3) and each output also comes as the collection
// of its N results (`<port>_all`), so a downstream block can take their mean or median. Up to
// `max_failures` repetitions may fail (a loop that found no marker): they are left out.
#include <boost/filesystem.hpp>
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>

#include "imagenets/executor.h"
#include "imagenets/registry.h"
#include "imagenets/sub_net_access.h"

namespace imagenets {
namespace {

// The collection type of an output type, or empty if it has none.
std::string collectionOf(const std::string& type) {
  if (type == "geometry_msgs/TransformStamped" || type == "geometry_msgs/PoseStamped") return "geometry_msgs/PoseArray";
  if (type == "std_msgs/Float64") return "std_msgs/Float64MultiArray";
  return "";
}

Value collect(const std::vector<Value>& values) {
  const std::string type = values.empty() ? "" : values.front().type->name;
  if (type == "std_msgs/Float64") {
    auto array = boost::make_shared<std_msgs::Float64MultiArray>();
    for (const auto& v : values) array->data.push_back(v.as<std_msgs::Float64>()->data);
    array->layout.dim.resize(1);
    array->layout.dim[0].label = "repetition";
    array->layout.dim[0].size = array->layout.dim[0].stride = array->data.size();
    return PortType::of<std_msgs::Float64MultiArray>().wrap<std_msgs::Float64MultiArray>(array);
  }
  auto poses = boost::make_shared<geometry_msgs::PoseArray>();
  for (const auto& v : values) {
    geometry_msgs::Pose pose;
    if (type == "geometry_msgs/TransformStamped") {
      auto t = v.as<geometry_msgs::TransformStamped>();
      poses->header = t->header;
      pose.position.x = t->transform.translation.x;
      pose.position.y = t->transform.translation.y;
      pose.position.z = t->transform.translation.z;
      pose.orientation = t->transform.rotation;
    } else {
      auto p = v.as<geometry_msgs::PoseStamped>();
      poses->header = p->header;
      pose = p->pose;
    }
    poses->poses.push_back(pose);
  }
  return PortType::of<geometry_msgs::PoseArray>().wrap<geometry_msgs::PoseArray>(poses);
}

std::string canonical(const std::string& path) {
  return boost::filesystem::weakly_canonical(boost::filesystem::absolute(path)).string();
}

}  // namespace

class SubNet : public Block, public SubNetAccess {
 public:
  SubNet() {
    addProperty<std::string>("net", "", "net file run as this block (relative to the including net)").path();
    addProperty<std::string>("net_yaml", "", "the sub-net written inline as YAML (instead of `net`)");
    addProperty<int>("repeat", 1, "runs of the sub-net per run; outputs also come as collections `<port>_all`")
        .range(1, 100000);
    addProperty<int>("max_failures", 0,
                     "repetitions that may fail (their results are left out); more fail the block")
        .range(0, 100000);
    addProperty<int>("threads", 0, "worker threads of the sub-net (0 = number of cores)").range(0, 64);
  }

  void configure() override {
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
      const BlockInfo* info = node.block->info();
      const bool is_input = info && info->type == "imagenets/ExecutorInput";
      const bool is_output = info && info->type == "imagenets/ExecutorOutput";
      if (!is_input && !is_output) continue;
      std::string port = std::get<std::string>(node.block->propertyValue("port"));
      if (port.empty()) port = node.name;
      const PortType& type = *node.block->inputs().front().type;
      if (is_input) {
        addInput(port, type, "sub-net input '" + node.name + "'");
        inputs_.push_back({port, node.name + ".value"});
      } else {
        addOutput(port, type, "sub-net output '" + node.name + "' (last repetition)");
        outputs_.push_back({port, node.name + ".value", collectionOf(type.name)});
        if (!outputs_.back().collection.empty()) {
          addOutput(port + "_all", *PortType::find(outputs_.back().collection),
                    "the results of all repetitions of '" + port + "'");
        }
      }
    }
  }

  void process(Context& ctx) override {
    if (!executor_) throw BlockError("no sub-net loaded");
    // One sub-net instance: concurrent calls (feedback trials) take turns.
    std::lock_guard<std::mutex> lock(run_mutex_);
    // The inner run's events reach the outer watchers as "<this block>/<inner block>"; the outer
    // cancel stops the inner run.
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
      if (!outputs_[o].collection.empty()) ctx.setOutput(outputs_[o].port + "_all", collect(results[o]));
    }
  }

  const Net* subNet() const override { return executor_ ? &executor_->net() : nullptr; }
  const Executor* subExecutor() const override { return executor_.get(); }

 private:
  // Nests the inner executor in the current outer run for the length of one process() call.
  struct Nesting {
    Nesting(Executor& inner, RunChannel outer) : inner(inner) { inner.nestIn(std::move(outer)); }
    ~Nesting() { inner.nestIn({}); }
    Executor& inner;
  };
  struct InPort {
    std::string port, inner;
  };
  struct OutPort {
    std::string port, inner, collection;
  };
  std::unique_ptr<Executor> executor_;
  std::mutex run_mutex_;
  std::vector<InPort> inputs_;
  std::vector<OutPort> outputs_;
};

}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::SubNet, "imagenets/Executor", "executor",
                         "Runs a net file as one block (sub-net), optionally N times");
