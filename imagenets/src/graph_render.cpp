#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "imagenets/graph.h"

namespace imagenets {

std::string renderDot(const std::string& dot, const std::string& format) {
  for (char c : format) {
    if (!std::isalnum(static_cast<unsigned char>(c))) throw std::runtime_error("bad Graphviz format '" + format + "'");
  }
  int to_child[2], from_child[2];
  if (pipe(to_child) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  if (pipe(from_child) != 0) {
    close(to_child[0]);
    close(to_child[1]);
    throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  }
  const std::string flag = "-T" + format;
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(to_child[0], 0);
    dup2(from_child[1], 1);
    close(to_child[0]);
    close(to_child[1]);
    close(from_child[0]);
    close(from_child[1]);
    execlp("dot", "dot", flag.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(to_child[0]);
  close(from_child[1]);
  if (pid < 0) {
    close(to_child[1]);
    close(from_child[0]);
    throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  }
  // Write on a second thread so a large picture cannot fill the pipe while we still write.
  std::thread writer([fd = to_child[1], &dot] {
    size_t done = 0;
    while (done < dot.size()) {
      const ssize_t n = write(fd, dot.data() + done, dot.size() - done);
      if (n <= 0) break;
      done += static_cast<size_t>(n);
    }
    close(fd);
  });
  std::string out;
  char buf[65536];
  ssize_t n;
  while ((n = read(from_child[0], buf, sizeof buf)) > 0) out.append(buf, static_cast<size_t>(n));
  close(from_child[0]);
  writer.join();
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) == 127) {
    throw std::runtime_error("cannot run Graphviz 'dot' (apt-get install graphviz)");
  }
  if (WEXITSTATUS(status) != 0) throw std::runtime_error("Graphviz 'dot " + flag + "' failed");
  return out;
}

}  // namespace imagenets
