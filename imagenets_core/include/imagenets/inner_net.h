// Implemented by a block that runs a whole net inside (imagenets/Executor): lets a host look at
// the inner net's cached values, e.g. the nodelet host's `publish_internal_ports`.
#pragma once

namespace imagenets {

class Executor;

class InnerNet {
 public:
  virtual ~InnerNet() = default;
  // The inner executor (null before configure()); its public API is thread-safe.
  virtual const Executor* innerExecutor() const = 0;
  // The same, to change it (e.g. a property of its blocks: net_wide_property.h).
  virtual Executor* innerExecutor() = 0;
};

}  // namespace imagenets
