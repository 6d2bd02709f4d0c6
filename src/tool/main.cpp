#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
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

int intValue(const Args& args, size_t& i) {
  const std::string& flag = args[i];
  const std::string v = flagValue(args, i);
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end || errno == ERANGE || n < INT_MIN || n > INT_MAX) {
    throw UsageError(flag + " '" + v + "' is not an integer");
  }
  return static_cast<int>(n);
}

double doubleValue(const Args& args, size_t& i) {
  const std::string& flag = args[i];
  const std::string v = flagValue(args, i);
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end || !std::isfinite(x)) throw UsageError(flag + " '" + v + "' is not a number");
  return x;
}

UsageError unknownArgument(const std::string& arg) {
  if (arg.size() > 1 && arg[0] == '-') return UsageError("unknown option '" + arg + "'");
  return UsageError("unexpected argument '" + arg + "'");
}

namespace {

bool isHelp(const std::string& arg) { return arg == "-h" || arg == "--help"; }

// One line per sub-command; `imagenets COMMAND --help` gives its options.
void printUsage(std::ostream& os) {
  size_t width = 0;
  for (const auto& c : commands()) width = std::max(width, c.name.size());
  os << "usage: imagenets COMMAND [ARGS]   (imagenets COMMAND --help: its arguments)\n\ncommands:\n";
  for (const auto& c : commands()) os << "  " << c.name << std::string(width + 2 - c.name.size(), ' ') << c.summary << "\n";
}

}  // namespace

}  // namespace tool
}  // namespace imagenets

int main(int argc, char** argv) {
  using namespace imagenets::tool;
  std::sort(commands().begin(), commands().end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  if (argc < 2 || isHelp(argv[1])) {
    printUsage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    Args args(argv + 2, argv + argc);
    // Help wins over everything else on the line, as in most command line tools.
    if (std::any_of(args.begin(), args.end(), isHelp)) {
      std::cout << "usage: imagenets " << c.usage << "\n\n" << c.summary << "\n";
      return 0;
    }
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
  printUsage(std::cerr);
  return 2;
}
