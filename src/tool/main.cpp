#include <iostream>

#include "command.h"
#include "imagenets/net.h"

namespace imagenets {
namespace tool {

std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}

std::string flagValue(const Args& args, size_t& i) {
  if (i + 1 >= args.size()) throw UsageError(args[i] + " needs a value");
  return args[++i];
}

}  // namespace tool
}  // namespace imagenets

int main(int argc, char** argv) {
  using namespace imagenets::tool;
  auto usage = [](std::ostream& os) {
    os << "usage: imagenets COMMAND [ARGS]\n\ncommands:\n";
    for (const auto& c : commands()) os << "  " << c.usage << "\n      " << c.summary << "\n";
  };
  if (argc < 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    usage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    Args args(argv + 2, argv + argc);
    try {
      return c.run(args);
    } catch (const UsageError& e) {
      std::cerr << "imagenets " << name << ": " << e.what() << "\nusage: imagenets " << c.usage << "\n";
      return 2;
    } catch (const imagenets::NetError& e) {
      std::cerr << e.what() << "\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << "imagenets " << name << ": " << e.what() << "\n";
      return 1;
    }
  }
  std::cerr << "imagenets: unknown command '" << name << "'\n";
  usage(std::cerr);
  return 2;
}
