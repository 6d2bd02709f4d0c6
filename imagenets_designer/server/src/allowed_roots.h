// The folders the Designer may open and save nets in (the net's folder, the package's config/,
// each --root): a path outside them is refused by name, so a page cannot read or write files
// elsewhere on the machine.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace imagenets {
namespace designer {

struct PathRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class AllowedRoots {
 public:
  void add(const std::string& dir);  // made absolute and canonical; duplicates ignored
  const std::vector<std::string>& roots() const { return roots_; }
  // `path` (relative: against `base`) as an absolute canonical path inside a root; throws
  // PathRefused naming the path and the roots otherwise.
  std::string check(const std::string& path, const std::string& base) const;

 private:
  std::vector<std::string> roots_;
};

}  // namespace designer
}  // namespace imagenets
