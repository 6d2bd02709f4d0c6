#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include <unistd.h>

#include "imagenets/tool/command.h"
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

// Folders searched for `imagenets-NAME` programs: the one the program was started from (e.g. a
// workspace's bin/), the running program's own and its workspace's bin/ (catkin puts a package's
// programs in lib/PACKAGE/, the commands' links in bin/), then PATH.
std::string started_from;  // argv[0]

std::vector<std::string> programFolders() {
  std::vector<std::string> dirs;
  if (started_from.find('/') != std::string::npos) {
    dirs.push_back(std::filesystem::path(started_from).parent_path().string());
  }
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    dirs.push_back(self.parent_path().string());
    dirs.push_back((self.parent_path().parent_path().parent_path() / "bin").string());
  }
  const char* path = std::getenv("PATH");
  std::stringstream list(path ? path : "");
  for (std::string dir; std::getline(list, dir, ':');) {
    if (!dir.empty()) dirs.push_back(dir);
  }
  return dirs;
}

std::string externalProgram(const std::string& name) {
  for (const auto& dir : programFolders()) {
    const std::string file = dir + "/imagenets-" + name;
    if (::access(file.c_str(), X_OK) == 0) return file;
  }
  return "";
}

// NAME -> program of every `imagenets-NAME` found (first one wins, as PATH does).
std::map<std::string, std::string> externalCommands() {
  std::map<std::string, std::string> found;
  for (const auto& dir : programFolders()) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
      const std::string file = e.path().filename().string();
      if (file.rfind("imagenets-", 0) != 0 || ::access(e.path().c_str(), X_OK) != 0) continue;
      found.emplace(file.substr(10), e.path().string());
    }
  }
  return found;
}

// The first line an external command prints for `--summary`.
std::string summaryOf(const std::string& program) {
  FILE* pipe = popen(("'" + program + "' --summary 2>/dev/null").c_str(), "r");
  if (!pipe) return "";
  char line[512] = "";
  if (!fgets(line, sizeof line, pipe)) line[0] = 0;
  pclose(pipe);
  std::string s(line);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// One line per sub-command; `imagenets COMMAND --help` gives its options.
void printUsage(std::ostream& os) {
  std::map<std::string, std::string> lines;
  for (const auto& c : commands()) lines[c.name] = c.summary;
  for (const auto& [name, program] : externalCommands()) {
    if (!lines.count(name)) lines[name] = summaryOf(program);
  }
  size_t width = 0;
  for (const auto& l : lines) width = std::max(width, l.first.size());
  os << "usage: imagenets COMMAND [ARGS]   (imagenets COMMAND --help: its arguments)\n\ncommands:\n";
  for (const auto& [name, summary] : lines) os << "  " << name << std::string(width + 2 - name.size(), ' ') << summary << "\n";
}

int runCommand(const Command& c, const Args& args) {
  // Help wins over everything else on the line, as in most command line tools.
  if (std::any_of(args.begin(), args.end(), isHelp)) {
    std::cout << "usage: imagenets " << c.usage << "\n\n" << c.summary << "\n";
    return 0;
  }
  try {
    return c.run(args);
  } catch (const UsageError& e) {
    std::cerr << "imagenets " << c.name << ": " << e.what() << "\nusage: imagenets " << c.usage << "\n";
    return 2;
  } catch (const imagenets::NetError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "imagenets " << c.name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int runCommandLine(int argc, char** argv) {
  std::sort(commands().begin(), commands().end(), [](const Command& a, const Command& b) { return a.name < b.name; });
  started_from = argv[0];
  const std::string program = std::filesystem::path(argv[0]).filename().string();
  if (program.rfind("imagenets-", 0) == 0) {
    // A program of its own: `imagenets-NAME ARGS`, usually started by `imagenets NAME ARGS`.
    const std::string name = program.substr(10);
    for (const auto& c : commands()) {
      if (c.name != name) continue;
      if (argc == 2 && std::string(argv[1]) == "--summary") {
        std::cout << c.summary << "\n";
        return 0;
      }
      return runCommand(c, Args(argv + 1, argv + argc));
    }
    std::cerr << program << ": no command '" << name << "' linked into this program\n";
    return 2;
  }
  if (argc < 2 || isHelp(argv[1])) {
    printUsage(argc < 2 ? std::cerr : std::cout);
    return argc < 2 ? 2 : 0;
  }
  const std::string name = argv[1];
  for (const auto& c : commands()) {
    if (c.name == name) return runCommand(c, Args(argv + 2, argv + argc));
  }
  const std::string external = externalProgram(name);
  if (!external.empty()) {
    std::vector<char*> args{const_cast<char*>(external.c_str())};
    for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    ::execv(external.c_str(), args.data());
    std::cerr << "imagenets: cannot run " << external << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  std::cerr << "imagenets: unknown command '" << name << "'\n";
  printUsage(std::cerr);
  return 2;
}

}  // namespace tool
}  // namespace imagenets
