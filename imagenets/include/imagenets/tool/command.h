// The `imagenets` command line: each sub-command is one file that registers itself with
// IMAGENETS_TOOL_COMMAND. Like git, `imagenets NAME` runs a program `imagenets-NAME` (beside the
// `imagenets` executable or on PATH) when no linked command has that name: packages add commands
// without the tool depending on them (their program's main calls runCommandLine too).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace imagenets {
namespace tool {

using Args = std::vector<std::string>;
struct Command {
  std::string name;
  std::string usage;    // "run NET [--set block.property=value ...] [--output-dir DIR]"
  std::string summary;  // one line
  std::function<int(const Args&)> run;  // returns the exit code
};

std::vector<Command>& commands();
struct CommandRegistration {
  explicit CommandRegistration(Command c) { commands().push_back(std::move(c)); }
};

// Thrown for bad command-line use; main prints it with the command's usage, exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Pops the value after a flag (`--output-dir DIR`); throws UsageError if missing.
std::string flagValue(const Args& args, size_t& i);
// The same, as a number: throws UsageError naming the flag and the value when it is not one.
int intValue(const Args& args, size_t& i);
double doubleValue(const Args& args, size_t& i);

// The error for an argument a command does not take: "unknown option '--x'" for anything that
// starts with '-', else "unexpected argument 'x'".
UsageError unknownArgument(const std::string& arg);

// The whole command line: `imagenets NAME ARGS` (argv[1] names the command), or, in a program
// named `imagenets-NAME`, `NAME ARGS`. Prints usage and errors; returns the exit code (2: usage).
int runCommandLine(int argc, char** argv);

}  // namespace tool
}  // namespace imagenets

#define IMAGENETS_TOOL_COMMAND(id, ...) \
  static ::imagenets::tool::CommandRegistration imagenets_tool_command_##id(::imagenets::tool::Command{__VA_ARGS__})
