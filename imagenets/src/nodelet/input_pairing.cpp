#include "input_pairing.h"

#include <cmath>

namespace imagenets {

InputPairing::InputPairing(std::vector<bool> required, PairingOptions options, bool source)
    : required_(std::move(required)), options_(options), source_(source), history_(required_.size()) {
  for (bool r : required_) any_required_ = any_required_ || r;
}

ros::Time InputPairing::stampOf(const Value& v) {
  return (v && v.type && v.type->stamp) ? v.type->stamp(v) : ros::Time();
}

std::vector<Value> InputPairing::latest() const {
  std::vector<Value> out(history_.size());
  for (size_t i = 0; i < history_.size(); ++i) {
    if (!history_[i].empty()) out[i] = history_[i].back();
  }
  return out;
}

Value InputPairing::partner(size_t input, const ros::Time& stamp) const {
  const auto& h = history_[input];
  if (h.empty()) return Value();
  // No reference time, or this input carries none: its latest value is its contribution.
  if (stamp.isZero() || stampOf(h.back()).isZero()) return h.back();
  Value best;
  double best_dt = 0.0;
  for (auto it = h.rbegin(); it != h.rend(); ++it) {
    const ros::Time t = stampOf(*it);
    if (t.isZero()) continue;
    const double dt = std::fabs((t - stamp).toSec());
    if (options_.approximate ? dt <= options_.slop : t == stamp) {
      if (!best || dt < best_dt) {
        best = *it;
        best_dt = dt;
      }
    }
  }
  return best;
}

bool InputPairing::add(size_t input, const Value& value, std::vector<Value>* set) {
  auto& h = history_.at(input);
  // A single input pairs with nothing: holding older messages would only keep their buffers
  // (images) alive, so the allocator cannot hand them out again.
  const size_t keep = history_.size() == 1 ? 1 : std::max<size_t>(1, options_.history);
  if (keep == 1 && !h.empty()) {
    h.back() = value;  // in place: no deque block handed out and back per message
  } else {
    h.push_back(value);
    while (h.size() > keep) h.pop_front();
  }
  if (isSource()) return false;
  if (history_.size() == 1) {
    set->assign(1, value);
    return true;
  }

  // The time this set is about: the arrival's stamp, or (for a time-less arrival) the newest
  // stamp held by a required input (by any input when none is required).
  ros::Time reference = stampOf(value);
  if (reference.isZero()) {
    for (size_t j = 0; j < history_.size() && reference.isZero(); ++j) {
      if (j != input && (required_[j] || !any_required_) && !history_[j].empty()) {
        reference = stampOf(history_[j].back());
      }
    }
  }
  std::vector<Value> found(history_.size());
  for (size_t j = 0; j < history_.size(); ++j) {
    if (j == input) {
      found[j] = value;
      continue;
    }
    found[j] = partner(j, reference);
    if (!found[j] && !required_[j] && !history_[j].empty()) found[j] = history_[j].back();
    if (!found[j] && required_[j]) return false;
  }
  *set = std::move(found);
  return true;
}

}  // namespace imagenets
