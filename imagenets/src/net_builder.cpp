#include "imagenets/net_builder.h"

#include <algorithm>

#include <imagenets/FeedbackTrace.h>

#include "imagenets/registry.h"

namespace imagenets {
namespace {

std::string describe(const BlockSpec& b) { return "block '" + b.name + "' (" + b.type + ")"; }

}  // namespace

NetBuilder::NetBuilder(const NetSpec& spec) : spec_(spec), scope_(spec_), net_(std::make_unique<Net>()) {
  net_->origin_ = spec.origin;
  net_->base_dir_ = spec.base_dir;
  net_->include_chain_ = spec.include_chain;
}

NetBuilder::~NetBuilder() = default;

void NetBuilder::createBlocks() {
  for (const BlockSpec& b : spec_.blocks) {
    const std::string at = b.loc.str() + ": ";
    if (b.name.empty() || b.name.find_first_of(". \t/") != std::string::npos) {
      errors_.push_back(at + "block name '" + b.name + "' may not contain '.', '/' or spaces");
      continue;
    }
    if (!names_.insert(b.name).second) {
      errors_.push_back(at + "block '" + b.name + "' defined twice");
      continue;
    }
    const BlockInfo* info = BlockRegistry::instance().findOrLoad(b.type);
    if (!info) {
      std::string msg = at + "block '" + b.name + "': unknown block type '" + b.type + "'";
      auto near = BlockRegistry::instance().suggest(b.type);
      if (!near.empty()) {
        msg += "; did you mean ";
        for (size_t i = 0; i < near.size(); ++i) msg += (i ? ", " : "") + std::string("'") + near[i] + "'";
        msg += "?";
      }
      errors_.push_back(msg);
      continue;
    }
    Net::Node node;
    node.name = b.name;
    node.loc = b.loc;
    node.feedback = b.feedback;
    node.block = BlockRegistry::instance().create(b.type);
    bool ok = true;
    for (const PropertySetting& s : b.properties) {
      try {
        node.block->setProperty(s.name, node.block->parseProperty(s.name, s.text, spec_.base_dir));
      } catch (const std::exception& e) {
        errors_.push_back(s.loc.str() + ": " + describe(b) + ": " + e.what());
        ok = false;
      }
    }
    if (!ok) continue;
    if (b.feedback) {
      node.block->attachOutput("feedback_trace", PortType::of<FeedbackTrace>(),
                               "every (value, score) of the feedback sweep and the chosen value");
    }
    try {
      node.block->configure();
    } catch (const NetError& e) {
      for (const auto& inner : e.errors()) errors_.push_back(at + describe(b) + ": " + inner);
      continue;
    } catch (const std::exception& e) {
      errors_.push_back(at + describe(b) + ": " + e.what());
      continue;
    }
    node.input_links.resize(node.block->inputs().size());
    net_->nodes_.push_back(std::move(node));
  }
}

void NetBuilder::linkBlocks() {
  // A block that failed to be created is skipped silently: its own error is reported.
  for (const LinkSpec& l : spec_.links) {
    const std::string at = l.loc.str() + ": link " + l.from_block + "." + l.from_port + " -> " + l.to_block + "." +
                           l.to_port + ": ";
    int from = net_->findNode(l.from_block), to = net_->findNode(l.to_block);
    if (from < 0 && !names_.count(l.from_block)) errors_.push_back(at + "no block named '" + l.from_block + "'");
    if (to < 0 && !names_.count(l.to_block)) errors_.push_back(at + "no block named '" + l.to_block + "'");
    if (from < 0 || to < 0) continue;
    const Block& src = *net_->nodes_[from].block;
    const Block& dst = *net_->nodes_[to].block;
    int out_port = src.outputIndex(l.from_port);
    int in_port = dst.inputIndex(l.to_port);
    if (out_port < 0) {
      errors_.push_back(at + "block '" + l.from_block + "' has no output port '" + l.from_port + "' (outputs: " +
                        portList(src.outputs()) + ")");
    }
    if (in_port < 0) {
      errors_.push_back(at + "block '" + l.to_block + "' has no input port '" + l.to_port + "' (inputs: " +
                        portList(dst.inputs()) + ")");
    }
    if (out_port < 0 || in_port < 0) continue;
    const std::string& out_type = src.outputs()[out_port].type->name;
    const std::string& in_type = dst.inputs()[in_port].type->name;
    if (out_type != in_type) {
      errors_.push_back(at + "type mismatch: output is " + out_type + ", input is " + in_type);
      continue;
    }
    Endpoint& slot = net_->nodes_[to].input_links[in_port];
    if (slot.valid()) {
      errors_.push_back(at + "input " + l.to_block + "." + l.to_port + " is already linked from " +
                        net_->nodes_[slot.node].name + "." + net_->nodes_[slot.node].block->outputs()[slot.port].name);
      continue;
    }
    slot = Endpoint{from, out_port};
    auto& down = net_->nodes_[from].downstream;
    if (std::find(down.begin(), down.end(), to) == down.end()) down.push_back(to);
  }
}

void NetBuilder::linkFeedbackInitials() {
  for (size_t i = 0; i < net_->nodes_.size(); ++i) {
    const Net::Node& n = net_->nodes_[i];
    if (!n.feedback) continue;
    const std::string at = n.feedback->loc.str() + ": block '" + n.name + "': feedback: initial ";
    for (const FeedbackInitial& init : n.feedback->initial) {
      if (!init.fromPort()) continue;
      const int from = net_->findNode(init.block);
      if (from < 0) {
        if (!names_.count(init.block)) errors_.push_back(at + init.str() + ": no block named '" + init.block + "'");
        continue;
      }
      const PortSpec* port = net_->nodes_[from].block->findOutput(init.port);
      if (!port) {
        errors_.push_back(at + init.str() + ": block '" + init.block + "' has no output port '" + init.port +
                          "' (outputs: " + portList(net_->nodes_[from].block->outputs()) + ")");
        continue;
      }
      if (port->type->name != "std_msgs/Float64") {
        errors_.push_back(at + init.str() + " is " + port->type->name + ", not std_msgs/Float64");
        continue;
      }
      const auto below = net_->descendants(static_cast<int>(i));
      if (from == static_cast<int>(i) || std::find(below.begin(), below.end(), from) != below.end()) {
        errors_.push_back(at + init.str() + ": block '" + init.block + "' is not upstream of the feedback region of '" +
                          n.name + "' (it must run before the sweep, outside the region)");
        continue;
      }
      auto& down = net_->nodes_[from].downstream;
      if (std::find(down.begin(), down.end(), static_cast<int>(i)) == down.end()) down.push_back(static_cast<int>(i));
    }
  }
}

void NetBuilder::orderBlocks() {
  // Event flow needs an acyclic net (feedback is declared on a block, never as a link).
  std::vector<int> indegree(net_->nodes_.size(), 0);
  for (const Net::Node& n : net_->nodes_) {
    for (int d : n.downstream) ++indegree[d];
  }
  std::vector<int> ready;
  for (size_t i = 0; i < indegree.size(); ++i) {
    if (indegree[i] == 0) ready.push_back(static_cast<int>(i));
  }
  net_->order_.clear();
  while (!ready.empty()) {
    int n = ready.front();
    ready.erase(ready.begin());
    net_->order_.push_back(n);
    for (int d : net_->nodes_[n].downstream) {
      if (--indegree[d] == 0) ready.push_back(d);
    }
  }
  if (net_->order_.size() == net_->nodes_.size()) return;
  std::string cycle;
  for (size_t i = 0; i < indegree.size(); ++i) {
    if (indegree[i] > 0) cycle += (cycle.empty() ? "" : ", ") + net_->nodes_[i].name;
  }
  errors_.push_back(spec_.origin + ": the links form a cycle through blocks " + cycle +
                    " (nets are acyclic; use feedback to tune a block from a downstream score)");
}

void NetBuilder::checkFeedback() {
  if (!errors_.empty()) return;  // the score's place in the net is only known in a whole net
  for (size_t i = 0; i < net_->nodes_.size(); ++i) {
    const Net::Node& n = net_->nodes_[i];
    if (!n.feedback) continue;
    const FeedbackSpec& f = *n.feedback;
    const std::string at = f.loc.str() + ": block '" + n.name + "': feedback: ";
    const PropertySpec* ps = n.block->findProperty(f.property);
    if (!ps) {
      errors_.push_back(at + "unknown property '" + f.property + "'");
    } else if (!ps->numeric()) {
      errors_.push_back(at + "property '" + f.property + "' is " + kindName(ps->kind()) + ", not numeric");
    } else {
      for (double v : f.values) {
        try {
          ps->fromNumber(v);
        } catch (const PropertyError& e) {
          errors_.push_back(at + "candidate for '" + f.property + "': " + e.what());
          break;
        }
      }
      for (const FeedbackInitial& init : f.initial) {
        if (init.fromPort()) continue;
        try {
          ps->fromNumber(init.value);
        } catch (const PropertyError& e) {
          errors_.push_back(at + "initial " + init.str() + " for '" + f.property + "': " + e.what());
        }
      }
    }
    int score = net_->findNode(f.score_block);
    if (score < 0) {
      errors_.push_back(at + "score block '" + f.score_block + "' does not exist");
      continue;
    }
    const PortSpec* port = net_->nodes_[score].block->findOutput(f.score_port);
    if (!port) {
      errors_.push_back(at + "score block '" + f.score_block + "' has no output port '" + f.score_port + "'");
      continue;
    }
    if (port->type->name != "std_msgs/Float64") {
      errors_.push_back(at + "score port " + f.score_block + "." + f.score_port + " is " + port->type->name +
                        ", not std_msgs/Float64");
      continue;
    }
    auto down = net_->descendants(static_cast<int>(i));
    if (score != static_cast<int>(i) && std::find(down.begin(), down.end(), score) == down.end()) {
      errors_.push_back(at + "score port " + f.score_block + "." + f.score_port + " is not downstream of block '" +
                        n.name + "'");
    }
  }
}

std::unique_ptr<Net> NetBuilder::finish() {
  if (!errors_.empty()) throw NetError(errors_);
  return std::move(net_);
}

}  // namespace imagenets
