// Undo and redo over the edited documents. A step is taken in two halves (target(), then
// stepped()) because installing the target into the executor may be refused, and then nothing
// must change.
#pragma once

#include <string>
#include <vector>

#include "net_document.h"

namespace imagenets {
namespace designer {

class EditHistory {
 public:
  enum class Direction { Undo, Redo };

  // `previous` was the document before an edit. Edits with the same non-empty `merge` key in a
  // row (one property dragged along a slider) make one undo step. A new edit drops the redos.
  void edited(NetDocument previous, const std::string& merge = "");
  // The document an undo (redo) goes back (forward) to; RequestError "nothing to undo" if none.
  const NetDocument& target(Direction direction) const;
  // The step to target(direction) is done; `current` is the document it replaced.
  void stepped(Direction direction, NetDocument current);
  void clear();

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }

 private:
  struct Snapshot {
    NetDocument doc;
    std::string merge;
  };
  std::vector<Snapshot> undo_, redo_;
};

}  // namespace designer
}  // namespace imagenets
