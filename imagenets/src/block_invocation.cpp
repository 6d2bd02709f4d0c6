#include "imagenets/block_invocation.h"

#include <chrono>

#include "imagenets/registry.h"
#include "imagenets/time.h"

namespace imagenets {

int missingInput(const Block& block, const std::vector<Value>& inputs) {
  for (size_t i = 0; i < block.inputs().size(); ++i) {
    if (!block.inputs()[i].optional && (i >= inputs.size() || !inputs[i])) return static_cast<int>(i);
  }
  return -1;
}

BlockInvocation invokeBlock(Block& block, const std::string& name, const std::vector<Value>& inputs,
                            std::shared_ptr<const PropertyValues> properties, InvocationOptions options) {
  BlockInvocation result;
  result.missing_input = missingInput(block, inputs);
  if (result.missing_input >= 0) {
    result.status = BlockStatus::NotRun;
    result.error = result.message = "input '" + block.inputs()[result.missing_input].name + "' has no value";
    result.outputs.resize(block.outputs().size());
    return result;
  }
  static const auto no_properties = std::make_shared<const PropertyValues>();
  Context ctx(name, block.inputs(), block.outputs(), inputs, properties ? std::move(properties) : no_properties);
  ctx.setRunChannel(std::move(options.channel));
  if (options.starting) options.starting();
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = options.cpu_time ? threadCpuMs() : 0.0;
  try {
    block.process(ctx);
  } catch (const RunCancelled&) {
    result.cancelled = ctx.cancelled();
    result.error = result.cancelled ? "cancelled" : "stopped as if cancelled, but the run was not cancelled";
  } catch (const std::exception& e) {
    result.error = e.what();
  } catch (...) {
    result.error = "unknown exception";
  }
  if (options.cpu_time) result.cpu_ms = threadCpuMs() - cpu_start;  // inside the wall-time interval
  result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.processed = true;
  if (result.cancelled) {
    result.status = BlockStatus::NotRun;
    result.message = result.error;
  } else if (result.error.empty()) {
    result.status = BlockStatus::Ok;
    result.outputs = std::move(ctx.outputs());
  } else {
    result.status = BlockStatus::Failed;
    result.message = "block '" + name + "' (" + (block.info() ? block.info()->type : std::string("?")) + "): " + result.error;
  }
  result.outputs.resize(block.outputs().size());
  return result;
}

}  // namespace imagenets
