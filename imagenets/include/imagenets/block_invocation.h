// The one way to run a block, whoever hosts it: the executor (nets, feedback trials, sub-nets),
// the nodelet host and the block test harness all call invokeBlock(), so a block test exercises
// exactly what production runs.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "imagenets/block.h"

namespace imagenets {

struct BlockInvocation {
  BlockStatus status = BlockStatus::Pending;  // Ok, Failed, or NotRun (a required input empty, or cancelled)
  std::string error;    // what process() threw, or "input 'x' has no value"; empty when Ok
  std::string message;  // for stats and logs: Failed: "block 'name' (type): error"; NotRun: `error`
  int missing_input = -1;   // NotRun: the required input without a value
  bool cancelled = false;   // NotRun: the block stopped early because its run was cancelled
  bool processed = false;   // process() was called (counts as a run in the stats, failed or not)
  double ms = 0.0;          // time spent in process()
  // CPU time of the calling thread in process() (not of threads it handed work to); NaN when not
  // asked for (InvocationOptions::cpu_time).
  double cpu_ms = std::numeric_limits<double>::quiet_NaN();
  std::vector<Value> outputs;  // per declared output port; all empty unless Ok
};

// The first required input of `block` without a value, or -1.
int missingInput(const Block& block, const std::vector<Value>& inputs);

// What a host adds to a call beyond the block and its data.
struct InvocationOptions {
  RunChannel channel;              // for blocks that run something inside (events out, cancel in)
  std::function<void()> starting;  // called just before process(), after the inputs were checked
  // Read the thread's CPU clock around process(): a system call (about 0.5 us each way), so a
  // host asks for it only when the time is shown.
  bool cpu_time = true;
};

// Checks the required inputs (per declared input port), builds the Context, calls
// `options.starting` and then process(), timed, catching every error; the outputs are checked
// against the declared ports as the block sets them (name, type). Never throws for what the block
// does. `inputs`: per declared input port (a shorter list leaves the last ones empty), read in
// place. `properties` null: the block has none.
BlockInvocation invokeBlock(Block& block, const std::string& name, const std::vector<Value>& inputs,
                            std::shared_ptr<const PropertyValues> properties, InvocationOptions options = {});

}  // namespace imagenets
