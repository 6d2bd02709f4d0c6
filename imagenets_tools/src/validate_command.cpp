// `imagenets validate NET`: load and check a net; OK or every load error. Exit 0 / 1.
#include <iostream>

#include "imagenets/tool/command.h"
#include "imagenets/executor.h"

namespace imagenets {
namespace tool {
namespace {

void declare(Flags& f) { f.operand("NET", 1, "the net file"); }

int run(const Options& o) {
  const Args args = strings(o, "NET");
  if (args.size() != 1) throw UsageError("expects one net file");
  try {
    Executor executor(Net::loadFile(args[0]), ExecutorOptions{1});
  } catch (const NetError& e) {
    std::cout << e.what() << "\n";
    return 1;
  }
  std::cout << "OK " << args[0] << "\n";
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(validate, "validate", "validate NET", "check a net file; prints OK or every error", declare, run);

}  // namespace tool
}  // namespace imagenets
