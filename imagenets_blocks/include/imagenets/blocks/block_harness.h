// For block tests: runs one block by type name outside any net, exactly the way every host runs
// it (invokeBlock: properties validated, configure() once, required inputs checked, process() on a
// fresh Context, outputs checked against the declared ports, stats recorded), so a test can feed
// inputs and read outputs of exactly that block.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "imagenets/block.h"
#include "imagenets/block_invocation.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace blocks {

class BlockHarness {
 public:
  explicit BlockHarness(const std::string& type) : block_(BlockRegistry::instance().create(type)) {}

  Block& block() { return *block_; }
  BlockHarness& set(const std::string& property, const PropertyValue& value) {
    block_->setProperty(property, value);
    return *this;
  }
  template <class M>
  BlockHarness& input(const std::string& port, const boost::shared_ptr<const M>& msg) {
    inputs_[port] = PortType::of<M>().wrap(msg);
    return *this;
  }
  template <class M>
  BlockHarness& input(const std::string& port, const boost::shared_ptr<M>& msg) {
    return input(port, boost::shared_ptr<const M>(msg));
  }
  BlockHarness& clear(const std::string& port) {
    inputs_.erase(port);
    return *this;
  }

  // Runs the block once; a failure (or a required input without a value) throws BlockError with
  // the block's own message. Outputs of a failed run are cleared.
  void run() {
    if (!configured_) {
      block_->configure();
      configured_ = true;
    }
    std::vector<Value> in;
    for (const auto& spec : block_->inputs()) {
      auto it = inputs_.find(spec.name);
      in.push_back(it == inputs_.end() ? Value{} : it->second);
    }
    outputs_.clear();
    BlockInvocation result = invokeBlock(*block_, "test", std::move(in), block_->propertySnapshot());
    stats_.record(result.status, result.message, result.ms, result.processed, result.cpu_ms);
    if (result.status != BlockStatus::Ok) throw BlockError(result.error);
    for (size_t i = 0; i < block_->outputs().size(); ++i) outputs_[block_->outputs()[i].name] = result.outputs[i];
  }
  const BlockStats& stats() const { return stats_; }
  // The error text of a run that must fail ("" if it did not fail).
  std::string runError() {
    try {
      run();
    } catch (const BlockError& e) {
      return e.what();
    }
    return "";
  }

  template <class M>
  boost::shared_ptr<const M> output(const std::string& port) const {
    auto it = outputs_.find(port);
    return it == outputs_.end() ? nullptr : it->second.as<M>();
  }
  bool hasOutput(const std::string& port) const {
    auto it = outputs_.find(port);
    return it != outputs_.end() && static_cast<bool>(it->second);
  }

 private:
  std::unique_ptr<Block> block_;
  bool configured_ = false;
  BlockStats stats_;
  std::map<std::string, Value> inputs_;
  std::map<std::string, Value> outputs_;
};

}  // namespace blocks
}  // namespace imagenets
