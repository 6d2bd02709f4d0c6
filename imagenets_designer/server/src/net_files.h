// The Designer's file operations, each inside the allowed folders: reading a net, saving one
// (written to a temporary file and renamed, so a failed save leaves the old file), listing a folder.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "allowed_roots.h"
#include "net_document.h"

namespace imagenets {
namespace designer {

class NetFiles {
 public:
  AllowedRoots& roots() { return roots_; }
  const AllowedRoots& roots() const { return roots_; }
  // `path` (relative: against `base`) inside a root, absolute; PathRefused otherwise.
  std::string check(const std::string& path, const std::string& base) const { return roots_.check(path, base); }

  // The text of a file; NetError naming it when it cannot be read.
  static std::string read(const std::string& path);
  // The net in `path` (as check() returned it), relative paths against its folder; NetError
  // with its lines.
  NetDocument load(const std::string& path) const;

  struct Saved {
    NetDocument doc;  // moved to the file's folder, its text now the source
    std::string text;
  };
  // `doc` written to `path` (as check() returned it). The text must load (the engine's parser judges it):
  // NetError otherwise, RequestError when it cannot be written.
  Saved save(const NetDocument& doc, const std::string& path) const;
  // The `list_files` reply for `dir` (as check() returned it): its entries, folders first, hidden ones left out.
  nlohmann::json list(const std::string& dir) const;

 private:
  AllowedRoots roots_;
};

}  // namespace designer
}  // namespace imagenets
