// imagenets/Executor, the ImageNet Executor block (paper 3.5): runs a net file as one block of
// another net. The inner net's port blocks (NetPort: imagenets/ExecutorInput / ExecutorOutput)
// become this block's ports. With `repeat: N` the inner net runs N times per run (paper 4.2, Fig.
// 4.3) and each output whose type has a collector (collectors.h) also comes as the collection of
// its N results (`<port>_all`), so a downstream block can take their mean or median. Up to
// `max_failures` repetitions may fail (a loop that found no marker): they are left out, and the
// output `failure` (declared when max_failures > 0) says why the first one failed; with
// max_failures >= N even a run whose repetitions all failed leaves the block ok (only `failure`
// comes out). `repetition_input: PORT` feeds the inner input port PORT (std_msgs/Int32) with the
// repetition's index 0..N-1 (pose k of N); `repeat_from_input: true` takes N from the input `repeat`.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "imagenets/block.h"
#include "imagenets/inner_net.h"

namespace imagenets {

struct Collector;
class Executor;

class SubNetBlock : public Block, public InnerNet {
 public:
  SubNetBlock();
  ~SubNetBlock() override;
  void configure() override;
  void process(Context& ctx) override;

  const Net* subNet() const override;
  const Executor* innerExecutor() const override { return executor_.get(); }
  Executor* innerExecutor() override { return executor_.get(); }

 private:
  struct InPort {
    std::string port, inner;
  };
  struct OutPort {
    std::string port, inner;
    const Collector* collector;  // null: no `<port>_all`
  };
  std::unique_ptr<Executor> executor_;
  std::mutex run_mutex_;
  std::vector<InPort> inputs_;
  std::vector<OutPort> outputs_;
  std::string repetition_input_;  // "block.value" of the inner port fed with the index, or empty
};

}  // namespace imagenets
