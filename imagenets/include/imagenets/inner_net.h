// Implemented by a block that runs a whole net inside (imagenets/SubNet): lets a host look at
// the inner net's cached values, e.g. the nodelet host's `publish_internal_ports`.
#pragma once

#include <string>
#include <vector>

namespace imagenets {

class Executor;

struct InnerExecutorRef {
  std::string path;  // under the block's name in run events: "" for the inner net, e.g. "until"
  Executor* executor;
};

class InnerNet {
 public:
  virtual ~InnerNet() = default;
  // Every net the block runs inside (the inner net, path "", and e.g. a sub-net's until net), to
  // change them (e.g. a property of their blocks: net_wide_property.h) or read their outputs
  // between runs; none before configure(). Their public API is thread-safe.
  virtual std::vector<InnerExecutorRef> innerExecutors() const = 0;
  // The inner net's executor (path ""); null before configure().
  const Executor* innerExecutor() const {
    for (const InnerExecutorRef& net : innerExecutors()) {
      if (net.path.empty()) return net.executor;
    }
    return nullptr;
  }
};

}  // namespace imagenets
