// The one way to run a block, whoever hosts it: the executor (nets, feedback trials, sub-nets),
// the nodelet host and the block test harness all call invokeBlock(), so a block test exercises
// exactly what production runs.
#pragma once

#include <functional>
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
  double cpu_ms = 0.0;      // CPU time of the calling thread in process() (not of threads it handed work to)
  std::vector<Value> outputs;  // per declared output port; all empty unless Ok
};

// The first required input of `block` without a value, or -1.
int missingInput(const Block& block, const std::vector<Value>& inputs);

// Checks the required inputs (per declared input port), builds the Context (with `channel` for
// blocks that run something inside), calls `starting` and then process(), timed, catching every
// error; the outputs are checked against the declared ports as the block sets them (name, type).
// Never throws for what the block does.
BlockInvocation invokeBlock(Block& block, const std::string& name, std::vector<Value> inputs,
                            PropertyValues properties, RunChannel channel = {},
                            const std::function<void()>& starting = {});

}  // namespace imagenets
