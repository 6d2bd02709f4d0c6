// The net the Designer edits: the engine's NetSpec plus the block positions on the canvas, and the
// text it was loaded from, so that saving an unchanged hand-written net gives back that text
// (comments, order, docs) with only the `designer: {positions: ...}` section updated.
#pragma once

#include <array>
#include <map>
#include <string>

#include "imagenets/net.h"

namespace imagenets {
namespace designer {

class NetDocument {
 public:
  using Positions = std::map<std::string, std::array<double, 2>>;

  // An empty net whose relative paths resolve against base_dir.
  static NetDocument empty(const std::string& origin, const std::string& base_dir);
  // Parses net-file text (throws NetError with `origin:line: ...` messages); positions come from
  // its `designer:` section.
  static NetDocument fromText(const std::string& text, const std::string& origin, const std::string& base_dir);

  NetSpec spec;
  Positions positions;

  // The net-file text: the loaded text when the net is unchanged, else the net written anew
  // (docs kept), each with the current positions in its `designer:` section.
  std::string text() const;
  // Same net (blocks, properties, feedback, links), positions and layout aside.
  bool sameNet(const NetDocument& other) const;
  // Another origin and folder (save as): relative path properties are rewritten so they still
  // name the same files from the new folder.
  void moveTo(const std::string& origin, const std::string& base_dir);

  // After a save or open: `text` is now the document's source (kept while the net is unchanged).
  void rebase(const std::string& text);

 private:
  std::string source_text_;     // the text loaded ("" for a new net)
  std::string source_written_;  // writeNetText of the spec as loaded: unchanged iff equal
};

}  // namespace designer
}  // namespace imagenets
