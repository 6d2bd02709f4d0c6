// The parsers of outside input that the fuzzers (scripts/fuzz, `make fuzz`) and the regression test
// (fuzz_regressions_test.cpp) feed: one function per target, named as the target.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace imagenets {
namespace fuzz {

struct Target {
  std::string name;     // "net_file": fuzzer fuzz_net_file, regressions in regressions/net_file/
  std::string seeds;    // shell glob of shipped files (from the repository root) seeding its corpus
  // Parses `input` as the product does; throws std::exception for input it refuses. `file` is the
  // path a file-reading parser reads it from (already written); an error must name it.
  std::function<void(const std::string& input, const std::string& file)> parse;
  bool reads_file = true;  // else the error need not name `file` (the input is text, not a file)
};

const std::vector<Target>& targets();
const Target& target(const std::string& name);  // throws std::out_of_range for an unknown name

}  // namespace fuzz
}  // namespace imagenets
