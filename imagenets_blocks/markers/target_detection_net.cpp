// The detection net for the target a target file describes: a net that measures "the target"
// (e.g. the calibration's sample net) takes any of them through this one block. A square marker
// needs a threshold search (its net: `marker_net`, e.g. calibration_marker_detection.yaml); an
// AprilTag or ChArUco target is found threshold-free (its net: `target_net`, e.g.
// calibration_target_detection.yaml, with imagenets/TargetDetector inside). Both nets are loaded
// with the block and must offer the same input ports; their outputs (the target net's a subset of
// the marker net's) are this block's. The target file is handed down: `target` to every block of
// the target net that has that property, the square marker's `marker` file to every block of the
// marker net that has that one. Like imagenets/SubNet with max_failures, a detection net that
// fails (nothing found) gives the output `failure` and leaves this block ok: not finding the target
// is a result.
#include <mutex>

#include <boost/make_shared.hpp>
#include <std_msgs/String.h>

#include "imagenets/executor.h"
#include "imagenets/inner_net.h"
#include "imagenets/net.h"
#include "imagenets/net_port.h"
#include "imagenets/net_wide_property.h"
#include "imagenets/register_block.h"
#include "imagenets/run_events.h"
#include "imagenets/vision/target.h"

namespace imagenets {
namespace blocks {

class TargetDetectionNet : public Block, public InnerNet {
 public:
  TargetDetectionNet() {
    addProperty("target", "", "target file (config/targets/); empty: marker_net as it is written").path();
    addProperty("marker_net", "", "detection net of a square marker (a threshold search)").path();
    addProperty("target_net", "", "detection net of an AprilTag or ChArUco target (same input ports)").path();
    addProperty<int>("threads", 1, "worker threads of the detection nets (0 = number of cores)").range(0, 64);
  }

  void configure() override {
    const std::string marker_file = property<std::string>("marker_net");
    const std::string target_file = property<std::string>("target_net");
    if (marker_file.empty()) throw BlockError("property 'marker_net': no net set");
    if (target_file.empty()) throw BlockError("property 'target_net': no net set");
    auto load = [&](const std::string& file) {
      NetSpec spec = parseNetFile(file);
      if (const NetSpec* outer = LoadContext::current()) {
        spec.include_chain = outer->include_chain;
        spec.include_chain.push_back(outer->origin);
      }
      return std::make_unique<Executor>(Net::build(spec), ExecutorOptions{property<int>("threads")});
    };
    marker_ = load(marker_file);
    target_ = load(target_file);
    inputs_.clear();
    outputs_.clear();
    const Net& marker_net = marker_->net();
    for (const std::string& name : netPortNames(marker_net, NetPort::Direction::In)) {
      const int node = findNetPort(marker_net, NetPort::Direction::In, name);
      const NetPort& port = netPortAt(marker_net, node);
      const std::string& block = marker_net.node(node).name;
      addInput(name, port.type(), "detection net input '" + block + "'").optional = port.optional();
      inputs_.push_back({name, block + ".value", ""});
    }
    for (const std::string& name : netPortNames(marker_net, NetPort::Direction::Out)) {
      const int node = findNetPort(marker_net, NetPort::Direction::Out, name);
      const std::string& block = marker_net.node(node).name;
      addOutput(name, netPortAt(marker_net, node).type(), "detection net output '" + block + "'");
      outputs_.push_back({name, block + ".value", ""});
    }
    // The target net: the same inputs, outputs among the marker net's.
    const Net& target_net = target_->net();
    for (const auto direction : {NetPort::Direction::In, NetPort::Direction::Out}) {
      auto& ports = direction == NetPort::Direction::In ? inputs_ : outputs_;
      const std::string kind = direction == NetPort::Direction::In ? "input" : "output";
      for (const std::string& name : netPortNames(target_net, direction)) {
        auto it = std::find_if(ports.begin(), ports.end(), [&](const Port& p) { return p.port == name; });
        if (it == ports.end()) {
          throw BlockError("property 'target_net': " + target_file + " has the " + kind + " '" + name + "', which " +
                           marker_file + " has not");
        }
        const int node = findNetPort(target_net, direction, name);
        const PortType& target_type = netPortAt(target_net, node).type();
        const PortType* type = direction == NetPort::Direction::In ? findInput(name)->type : findOutput(name)->type;
        if (type->name != target_type.name) {
          throw BlockError("property 'target_net': " + kind + " '" + name + "' is " + target_type.name + " in " +
                           target_file + " but " + type->name + " in " + marker_file);
        }
        it->target_inner = target_net.node(node).name + ".value";
      }
    }
    for (const Port& in : inputs_) {
      if (in.target_inner.empty()) {
        throw BlockError("property 'target_net': " + target_file + " has no input '" + in.port + "' (" + marker_file +
                         " has)");
      }
    }
    addOutput<std_msgs::String>("failure", "why the detection net found nothing; only then (the block stays ok)");
    if (!property<std::string>("target").empty()) targetOf(property<std::string>("target"));
  }

  void process(Context& ctx) override {
    std::lock_guard<std::mutex> lock(mutex_);
    const std::string path = ctx.property<std::string>("target");
    const auto target = path.empty() ? nullptr : targetOf(path);
    const bool square = !target || target->type == target::TargetType::SquareMarker;
    Executor& exec = square ? *marker_ : *target_;
    // The target down to the blocks that read it (once per change: a set property re-runs them).
    if (target && handed_down_[square] != path) {
      if (square) setPropertyInNetTree(exec, "marker", target->marker_file);
      else setPropertyInNetTree(exec, "target", path);
      handed_down_[square] = path;
    }
    exec.nestIn(ctx.innerChannel());
    struct Unnest {
      Executor& e;
      ~Unnest() { e.nestIn({}); }
    } unnest{exec};
    for (const Port& in : inputs_) exec.setInput(square ? in.inner : in.target_inner, ctx.inputValue(in.port));
    const RunReport report = exec.run();
    if (report.cancelled) throw RunCancelled();
    if (!report.failed.empty()) {
      auto why = boost::make_shared<std_msgs::String>();
      why->data = report.failed.front();
      ctx.output("failure", why);
      return;
    }
    for (const Port& out : outputs_) {
      const std::string& inner = square ? out.inner : out.target_inner;
      if (inner.empty()) continue;
      const Value v = exec.output(inner);
      if (v) ctx.setOutput(out.port, v);
    }
  }

  std::vector<InnerExecutorRef> innerExecutors() const override {
    std::vector<InnerExecutorRef> nets;
    if (marker_) nets.push_back({"", marker_.get()});
    if (target_) nets.push_back({"target", target_.get()});
    return nets;
  }
  const Net* subNet() const override { return marker_ ? &marker_->net() : nullptr; }

 private:
  struct Port {
    std::string port, inner, target_inner;  // inner: "block.value" in the marker net, target_inner: in the target net
  };

  static std::shared_ptr<const target::TargetDescription> targetOf(const std::string& path) {
    try {
      return target::TargetDescription::loadCached(path);
    } catch (const std::exception& e) {
      throw BlockError(std::string("property 'target': ") + e.what());
    }
  }

  std::unique_ptr<Executor> marker_, target_;
  std::vector<Port> inputs_, outputs_;
  std::string handed_down_[2];  // the target file last handed to the target net [0] / marker net [1]
  std::mutex mutex_;
};

}  // namespace blocks
}  // namespace imagenets

IMAGENETS_REGISTER_BLOCK(imagenets::blocks::TargetDetectionNet, "imagenets/TargetDetectionNet", "markers",
                         "Runs the detection net of the target file's kind (square marker, AprilTag, ChArUco)");
