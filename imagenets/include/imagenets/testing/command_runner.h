// For tests of command line programs: run one as a user does, in a shell, and look at what it said.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

namespace imagenets {
namespace testing {

struct CommandResult {
  int status;
  std::string output;
};

// Runs `program ARGS` in a shell (ARGS may use the shell: `$(rospack find ...)`); returns the exit
// status and stdout + stderr (only stdout with stdout_only).
inline CommandResult runCommand(const std::string& program, const std::string& args, bool stdout_only = false) {
  const std::string cmd = program + " " + args + (stdout_only ? " 2>/dev/null" : " 2>&1");
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  size_t n;
  while (pipe && (n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

#ifdef IMAGENETS_TOOL
// `imagenets ARGS`, run as runCommand runs it, in the test's working folder. IMAGENETS_TOOL is the
// program's path: the test target defines it (target_compile_definitions in its CMakeLists).
inline CommandResult tool(const std::string& args, bool stdout_only = false) {
  return runCommand(IMAGENETS_TOOL, args, stdout_only);
}
#endif

inline void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in:\n" << text;
}

// A file name in a temporary folder of this test process.
inline std::string tempPath(const std::string& name) {
  auto dir = boost::filesystem::temp_directory_path() / ("imagenets_test_" + std::to_string(getpid()));
  boost::filesystem::create_directories(dir);
  return (dir / name).string();
}

}  // namespace testing
}  // namespace imagenets
