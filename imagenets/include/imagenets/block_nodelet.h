// The nodelet host: every registered block is also the nodelet `imagenets/<BlockName>`
// (IMAGENETS_REGISTER_BLOCK exports imagenets::BlockNodelet<Class>). One generic host, no
// per-block code:
//   - each input port `port` is the topic ~in/port (subscribed), each output ~out/port
//     (advertised): most blocks have an input and an output of the same name ("image"), and one
//     topic cannot be remapped two ways. A launch file links blocks by remapping an input to
//     another block's output (<remap from="~in/image" to="gray/out/image"/>). Inside one manager
//     messages pass as ConstPtr (zero-copy).
//   - several inputs are paired by header stamp (exact, or approximate within a slop);
//     header-less inputs (std_msgs/Float64, ...) take their latest value.
//   - a block without required or linked (remapped) inputs, a source, runs once, on a timer or
//     on ~run; a block whose inputs are all optional but linked runs on every arrival.
//   - properties come from ~private parameters (same checks and messages as net files) and can
//     be changed live through the dynamic_reconfigure protocol (~set_parameters,
//     ~parameter_descriptions, ~parameter_updates); a change re-runs the block on its cached
//     inputs, which refreshes everything downstream.
//   - ~run (std_srvs/Trigger) re-runs the block; ~status (latched imagenets/BlockNodeletStatus) reports.
//   - a block running a net inside (imagenets/SubNet) can publish every inner output port as
//     ~internal/<block>/<port> (property publish_internal_ports), only while subscribed.
// The logic lives in block_nodelet.cpp; this header stays light because every block includes it.
#pragma once

#include <memory>

#include <nodelet/nodelet.h>

#include "imagenets/block.h"

namespace imagenets {

class BlockHost;

class BlockNodeletBase : public nodelet::Nodelet {
 public:
  BlockNodeletBase();
  ~BlockNodeletBase() override;

 protected:
  virtual std::unique_ptr<Block> createBlock() const = 0;

 private:
  void onInit() final;
  std::unique_ptr<BlockHost> host_;
};

template <class BlockClass>
class BlockNodelet : public BlockNodeletBase {
 protected:
  std::unique_ptr<Block> createBlock() const override { return std::make_unique<BlockClass>(); }
};

}  // namespace imagenets
