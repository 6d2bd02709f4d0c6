// Builds a Net from its spec in named steps, each collecting every error it finds (with file:line)
// instead of stopping at the first: Net::build runs them in order. A step works on what the steps
// before it built, so a test can run the first steps and look at their errors.
//
//   NetBuilder b(spec);
//   b.createBlocks();   // types, properties, configure()
//   b.linkBlocks();     // links resolved and type-checked
//   b.linkFeedbackInitials();  // `initial: block.port` feeds the tuned block like a link
//   b.orderBlocks();    // acyclic: the event-flow order
//   b.checkFeedback();  // feedback declarations against the built net
//   std::unique_ptr<Net> net = b.finish();  // throws NetError listing every error
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "imagenets/net.h"

namespace imagenets {

class NetBuilder {
 public:
  explicit NetBuilder(const NetSpec& spec);
  ~NetBuilder();

  // Creates each block of a known type, sets its properties (checked), adds the engine's outputs
  // (feedback_trace) and configures it. A block with an error is left out of the net.
  void createBlocks();
  // Resolves each link to ports of created blocks, checking names and types; one link per input.
  void linkBlocks();
  // Feedback candidates taken from another block's output (`initial: block.port`): that block must
  // run before the sweep, so it feeds the tuned block like a link (it joins the dependency order).
  void linkFeedbackInitials();
  // Orders the blocks for event flow; lists the blocks of a cycle.
  void orderBlocks();
  // Checks each feedback declaration: a numeric property, valid candidates, a Float64 score port
  // downstream of the block. Only when the steps before found no error.
  void checkFeedback();

  const std::vector<std::string>& errors() const { return errors_; }
  const Net& net() const { return *net_; }
  // The net; throws NetError listing every error of every step.
  std::unique_ptr<Net> finish();

 private:
  const NetSpec spec_;        // a copy: the builder may outlive the caller's spec
  LoadContext::Scope scope_;  // blocks' configure() sees the net being built
  std::unique_ptr<Net> net_;
  std::set<std::string> names_;  // every block declared, created or not
  std::vector<std::string> errors_;
};

}  // namespace imagenets
