#include "allowed_roots.h"

#include <algorithm>

#include <boost/filesystem.hpp>

namespace imagenets {
namespace designer {

namespace fs = boost::filesystem;

void AllowedRoots::add(const std::string& dir) {
  const std::string root = fs::weakly_canonical(fs::absolute(dir)).string();
  if (std::find(roots_.begin(), roots_.end(), root) == roots_.end()) roots_.push_back(root);
}

std::string AllowedRoots::check(const std::string& path, const std::string& base) const {
  // Symbolic links and `..` are resolved first, so neither leads out of a root.
  const fs::path p = fs::path(path).is_absolute() ? fs::path(path) : fs::path(base) / path;
  const std::string canonical = fs::weakly_canonical(p).string();
  for (const auto& root : roots_) {
    if (canonical == root || canonical.compare(0, root.size() + 1, root + "/") == 0) return canonical;
  }
  std::string list;
  for (const auto& root : roots_) list += (list.empty() ? "" : ", ") + root;
  throw PathRefused("path '" + path + "' is outside the allowed folders (" + list +
                    "; start the designer with --root DIR to allow another)");
}

}  // namespace designer
}  // namespace imagenets
