#include "edit_history.h"

#include "request_error.h"

namespace imagenets {
namespace designer {

void EditHistory::edited(NetDocument previous, const std::string& merge) {
  if (merge.empty() || undo_.empty() || undo_.back().merge != merge || !redo_.empty()) {
    undo_.push_back({std::move(previous), merge});
  }
  redo_.clear();
}

const NetDocument& EditHistory::target(Direction direction) const {
  const auto& from = direction == Direction::Undo ? undo_ : redo_;
  if (from.empty()) throw RequestError(direction == Direction::Undo ? "nothing to undo" : "nothing to redo");
  return from.back().doc;
}

void EditHistory::stepped(Direction direction, NetDocument current) {
  auto& from = direction == Direction::Undo ? undo_ : redo_;
  auto& to = direction == Direction::Undo ? redo_ : undo_;
  from.pop_back();
  to.push_back({std::move(current), ""});
}

void EditHistory::clear() {
  undo_.clear();
  redo_.clear();
}

}  // namespace designer
}  // namespace imagenets
