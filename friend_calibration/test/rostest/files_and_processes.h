// What the rostests of this folder share around files and processes: a file's bytes (readFile, from
// imagenets/testing/read_file.h), and a program (a node, robot_state_publisher) started as a child
// process, its output in a log file if asked (a message on /rosout sent while a node starts could
// be lost before the test's connection is up; what the node prints is not). A command run to its
// end: imagenets/testing/command_runner.h.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

#include <ros/ros.h>

#include "imagenets/testing/read_file.h"
#include "imagenets/testing/rostest_util.h"

using imagenets::testing::readFile;

// A child process, stopped with SIGINT when it goes (SIGKILL if it has not ended 30 s later).
class ChildProcess {
 public:
  ChildProcess() = default;
  explicit ChildProcess(std::vector<std::string> args, const std::string& log = "") { start(std::move(args), log); }
  ~ChildProcess() { stop(); }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Starts `args` (the program looked up on PATH); with `log`, its stdout and stderr go to that
  // file. posix_spawn, not fork: the test runs spinner threads.
  void start(std::vector<std::string> args, const std::string& log = "") {
    stop();
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!log.empty()) {
      posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    }
    if (posix_spawnp(&pid_, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  // Its exit status once it ended by itself within `seconds` (-1: still running; 128: killed by a
  // signal).
  int exitStatus(double seconds) {
    int status = 0;
    const bool ended = waitFor([&] { return waitpid(pid_, &status, WNOHANG) == pid_; }, seconds);
    if (!ended) return -1;
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  }

  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGINT);
    bool ended = false;
    for (int i = 0; i < 300 && !(ended = waitpid(pid_, nullptr, WNOHANG) == pid_); ++i) ros::WallDuration(0.1).sleep();
    if (!ended) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    pid_ = -1;
  }

 private:
  pid_t pid_ = -1;
};
