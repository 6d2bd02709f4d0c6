// imagenets/SubNet, the sub-net block (the paper's ImageNet Executor, 3.5): runs a net file as one block of
// another net. The inner net's port blocks (NetPort: imagenets/SubNetInput / SubNetOutput)
// become this block's ports. With `repeat: N` the inner net runs N times per run (paper 4.2, Fig.
// 4.3) and each output whose type has a collector (collectors.h) also comes as the collection of
// its N results (`<port>_all`), so a downstream block can take their mean or median. Up to
// `max_failures` repetitions may fail (a loop that found no marker): they are left out, and the
// output `failure` (declared when max_failures > 0) says why the first one failed; with
// max_failures >= N even a run whose repetitions all failed leaves the block ok (only `failure`
// comes out). `repetition_input: PORT` feeds the inner input port PORT (std_msgs/Int32) with the
// repetition's index 0..N-1 (pose k of N); `repeat_from_input: true` takes N from the input `repeat`.
//
// Repeat until: with `until_net: FILE` the repetitions go on past N, one at a time, until that net
// says `done` or `max_repeat` ran (the input `max_repeat` when it has a value, else the property).
// The until net runs after repetition N and after each one added; its inputs are fed by name from
// this block's inputs (e.g. `plan`) and from the collections so far (`<port>_all`), and its
// std_msgs/Bool output `done` stops the repetitions when true (a run of it that fails counts as not
// done). Its run events come as "<this block>/until/<block>", before the repetition's event, so an
// observer of that event can read the until net's outputs (innerExecutors(): path "until"); the
// repetition events' count is then the most that may run (max_repeat).
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
  std::vector<InnerExecutorRef> innerExecutors() const override;

 private:
  struct InPort {
    std::string port, inner;
  };
  struct OutPort {
    std::string port, inner;
    const Collector* collector;  // null: no `<port>_all`
  };
  struct UntilInPort {
    std::string inner;  // "block.value" in the until net
    int input = -1;     // index in inputs_, or
    int output = -1;    // index in outputs_ whose collection so far feeds it
  };
  // Runs the until net on the repetitions so far (`inputs`: this run's input values, as inputs_);
  // true when it says done. `verdict`: what it said, for the repetition's event (a failed until
  // net repeats, and says why).
  bool untilDone(const std::vector<std::vector<Value>>& results, const std::vector<Value>& inputs,
                 std::string* verdict);

  // The steps of configure(): this block's ports from the inner net's port blocks (`origin` names
  // it in errors); the until net and its inputs, each matched to an input or a collection.
  void declarePorts(const std::string& origin);
  void configureUntil(const std::vector<std::string>& chain);
  UntilInPort untilInput(const std::string& block, const std::string& port, const PortType& type,
                         const std::string& origin) const;

  // What the repetitions of one run gave.
  struct Repetitions {
    std::vector<std::vector<Value>> results;  // per output, of the repetitions that succeeded
    int failures = 0, ran = 0;
    std::string first_failure, first_failure_message;
  };
  // The steps of process(): how many repetitions at least and at most; one repetition (true: no
  // more are needed); the outputs from them, or the error when too many failed.
  int repetitions(Context& ctx) const;
  int maxRepetitions(Context& ctx, int repeat) const;
  bool repeatOnce(int i, int repeat, int max_repeat, Context& ctx, const std::vector<Value>& inputs, Repetitions& r);
  void setOutputs(Context& ctx, const Repetitions& r) const;

  std::unique_ptr<Executor> executor_;
  std::unique_ptr<Executor> until_;
  std::vector<UntilInPort> until_inputs_;
  std::string until_done_;  // "block.value" of the until net's output `done`
  std::mutex run_mutex_;
  std::vector<InPort> inputs_;
  std::vector<OutPort> outputs_;
  std::string repetition_input_;  // "block.value" of the inner port fed with the index, or empty
};

}  // namespace imagenets
