#include <algorithm>
#include <cerrno>
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

Flags::Flags() : flags_("options"), operands_("operands") {}

void Flags::operand(const std::string& name, int count, const std::string& help) {
  operands_.add_options()(name.c_str(), po::value<std::vector<std::string>>(), help.c_str());
  positional_.add(name.c_str(), count);
  operand_names_.emplace_back(name, count);
}

namespace {

// What a typed flag expects, for "--n 'many' is not an integer".
std::string expected(const po::options_description& flags, const std::string& option) {
  const std::string name = option.substr(option.find_first_not_of('-'));
  const po::option_description* d = flags.find_nothrow(name, false);
  const po::value_semantic* s = d ? d->semantic().get() : nullptr;
  if (dynamic_cast<const po::typed_value<int>*>(s)) return "an integer";
  if (dynamic_cast<const po::typed_value<double>*>(s)) return "a number";
  return "valid";
}

}  // namespace

Options Flags::parse(const Args& given) const {
  Args args;
  for (const auto& a : given) {
    if (!(ros_arguments_ && a.rfind("__", 0) == 0 && a.find(":=") != std::string::npos)) args.push_back(a);
  }
  po::options_description all;
  all.add(flags_).add(operands_);
  // Arguments past the last operand: named in the error.
  all.add_options()("imagenets-extra-operand", po::value<std::vector<std::string>>(), "");
  po::positional_options_description positional = positional_;
  if (operand_names_.empty() || operand_names_.back().second >= 0) positional.add("imagenets-extra-operand", -1);
  Options o;
  try {
    po::store(po::command_line_parser(args)
                  .options(all)
                  .positional(positional)
                  .style(po::command_line_style::default_style & ~po::command_line_style::allow_guessing)
                  .run(),
              o);
    po::notify(o);
  } catch (const po::unknown_option& e) {
    throw UsageError("unknown option '" + e.get_option_name() + "'");
  } catch (const po::invalid_option_value& e) {
    // "the argument ('many') for option '--threads' is invalid"
    const std::string what = e.what();
    const auto open = what.find("('"), close = what.find("')");
    const std::string value = open != std::string::npos && close > open ? what.substr(open + 2, close - open - 2) : "";
    throw UsageError(e.get_option_name() + " '" + value + "' is not " + expected(flags_, e.get_option_name()));
  } catch (const po::invalid_command_line_syntax& e) {
    if (e.kind() == po::invalid_syntax::missing_parameter) throw UsageError(e.get_option_name() + " needs a value");
    throw UsageError(e.what());
  } catch (const po::error& e) {
    throw UsageError(e.what());
  }
  if (o.count("imagenets-extra-operand")) {
    throw UsageError("unexpected argument '" + o["imagenets-extra-operand"].as<std::vector<std::string>>().front() + "'");
  }
  return o;
}

void Flags::printHelp(std::ostream& os) const {
  if (!flags_.options().empty()) os << "\n" << flags_;
  if (operand_names_.empty()) return;
  os << "\noperands:\n";
  for (const auto& d : operands_.options()) os << "  " << d->long_name() << "  " << d->description() << "\n";
}

std::vector<std::string> strings(const Options& o, const std::string& name) {
  return o.count(name) ? o[name].as<std::vector<std::string>>() : std::vector<std::string>{};
}

std::string stringFlag(const Options& o, const std::string& name) {
  return o.count(name) ? o[name].as<std::string>() : std::string();
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
  Flags flags;
  if (c.declare) c.declare(flags);
  // Help wins over everything else on the line, as in most command line tools.
  if (std::any_of(args.begin(), args.end(), isHelp)) {
    std::cout << "usage: imagenets " << c.usage << "\n\n" << c.summary << "\n";
    flags.printHelp(std::cout);
    return 0;
  }
  try {
    return c.run(flags.parse(args));
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
