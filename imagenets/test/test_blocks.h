// Small blocks for the engine's tests: they count their calls, meet at a barrier, fail on demand
// and compute known scores, so tests can assert what the executor did.
#pragma once

#include <atomic>
#include <map>
#include <mutex>
#include <string>

namespace imagenets {
namespace test {

// process() calls per block name, since the last reset.
int calls(const std::string& block_name);
void resetCalls();

}  // namespace test
}  // namespace imagenets
