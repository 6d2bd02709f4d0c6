// Pairs the inputs of a multi-input block nodelet by header stamp (the nodelet host's event flow).
// Each arrival is checked against the other inputs' recent messages: when every required input
// has a partner for the arrival's stamp (equal stamps, or within `slop` seconds in approximate
// mode), the set is complete and the block runs once with it. Messages are kept after use, so a
// re-published input (a property changed upstream) pairs again with the unchanged ones.
// A message with a zero stamp (a type without header, e.g. std_msgs/Float64, or an unset header)
// carries no time: its input contributes its latest value to any set. Optional inputs contribute
// their stamp match if there is one, else their latest value (or nothing); a block whose inputs are
// all optional runs on every arrival.
#pragma once

#include <deque>
#include <vector>

#include <ros/time.h>

#include "imagenets/port_type.h"

namespace imagenets {

struct PairingOptions {
  bool approximate = false;
  double slop = 0.05;    // seconds, approximate mode only
  size_t history = 5;    // messages kept per input
};

class InputPairing {
 public:
  // `required[i]`: input i must be present for a run. `source`: the block runs on a timer or on
  // demand, never on arrival (the host's choice for a block with no linked input).
  InputPairing(std::vector<bool> required, PairingOptions options, bool source = false);
  void setOptions(const PairingOptions& options) { options_ = options; }
  const PairingOptions& options() const { return options_; }
  bool isSource() const { return source_; }

  // Records `value` on `input`; when this arrival completes an input set, writes it to `set` (one
  // value per input; nothing is allocated when `set` has that size already) and returns true.
  bool add(size_t input, const Value& value, std::vector<Value>* set);
  // The latest value of every input (for sources: what the optional inputs hold now).
  std::vector<Value> latest() const;

 private:
  static ros::Time stampOf(const Value& v);
  // The message of `input` to pair with `stamp` (zero: the latest); empty if none fits.
  Value partner(size_t input, const ros::Time& stamp) const;

  std::vector<bool> required_;
  bool any_required_ = false;
  PairingOptions options_;
  bool source_ = false;
  std::vector<std::deque<Value>> history_;  // newest last
};

}  // namespace imagenets
