// The `imagenets` command line: each sub-command is one file that registers itself with
// IMAGENETS_TOOL_COMMAND. Like git, `imagenets NAME` runs a program `imagenets-NAME` (beside the
// `imagenets` executable or on PATH) when no linked command has that name: packages add commands
// without the tool depending on them (their program's main calls runCommandLine too).
//
// A command declares its flags and operands once (Boost.Program_options): parsing, defaults,
// `--help` and the errors for unknown or malformed flags all come from that declaration.
//
//   void declare(Flags& f) {
//     f.add()("threads", po::value<int>()->default_value(0), "worker threads (0 = cores)")
//            ("quiet,q", po::bool_switch(), "print only the result");
//     f.operand("NET", 1, "the net file");
//   }
//   int run(const Options& o) { ... o["threads"].as<int>() ... strings(o, "NET") ... }
//   IMAGENETS_TOOL_COMMAND(run, "run", "run NET [options]", "run a net", declare, run);
#pragma once

#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>

namespace imagenets {
namespace tool {

namespace po = boost::program_options;
using Args = std::vector<std::string>;
using Options = po::variables_map;

// Thrown for bad command-line use; main prints it with the command's usage, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One command's flags and operands.
class Flags {
 public:
  Flags();
  // Declares flags: add()("name,n", po::value<T>()->default_value(x), "help") ... (no guessing
  // of abbreviations; a repeated flag needs a std::vector value).
  po::options_description_easy_init add() { return flags_.add_options(); }
  // The operands (arguments that are not flags), in order: `count` of them named `name` in
  // the help (-1: any number, only for the last one). Read them with strings(o, name).
  void operand(const std::string& name, int count, const std::string& help);
  // roslaunch passes `__name:=...` and `__log:=...` to a node it starts: the command ignores them.
  void acceptRosArguments() { ros_arguments_ = true; }

  // Throws UsageError: "unknown option '--x'", "unexpected argument 'x'", "--n 'many' is not an
  // integer", "--x needs a value".
  Options parse(const Args& args) const;
  // The flags with their defaults and help, then the operands.
  void printHelp(std::ostream& os) const;

 private:
  po::options_description flags_, operands_;
  po::positional_options_description positional_;
  std::vector<std::pair<std::string, int>> operand_names_;
  bool ros_arguments_ = false;
};

// The values of operands or of a repeated flag (a std::vector<std::string>), empty when none.
std::vector<std::string> strings(const Options& o, const std::string& name);
// The value of a flag that has no default, or "" when not given.
std::string stringFlag(const Options& o, const std::string& name);

struct Command {
  std::string name;
  std::string usage;    // the line in short: "run NET [--set block.property=value ...]"
  std::string summary;  // one line
  std::function<void(Flags&)> declare;     // its flags and operands
  std::function<int(const Options&)> run;  // returns the exit code
};

std::vector<Command>& commands();
struct CommandRegistration {
  explicit CommandRegistration(Command c) { commands().push_back(std::move(c)); }
};

// The whole command line: `imagenets NAME ARGS` (argv[1] names the command), or, in a program
// named `imagenets-NAME`, `NAME ARGS`. Prints usage and errors; returns the exit code (2: usage).
int runCommandLine(int argc, char** argv);

}  // namespace tool
}  // namespace imagenets

#define IMAGENETS_TOOL_COMMAND(id, ...) \
  static ::imagenets::tool::CommandRegistration imagenets_tool_command_##id(::imagenets::tool::Command{__VA_ARGS__})
