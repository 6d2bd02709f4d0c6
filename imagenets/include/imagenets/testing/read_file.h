// For tests that look at what a program or block wrote: a file's bytes as one string.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace imagenets {
namespace testing {

// The file's bytes ("" when it cannot be read).
inline std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace testing
}  // namespace imagenets
