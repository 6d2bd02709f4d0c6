// One setting for a whole net tree: a property set on every block that declares it, in the net
// and in the nets its sub-net blocks run inside (InnerNet: the sub-net, its until net) at any depth. For a value that every block of
// a family reads from a property of one name, e.g. the robot description a calibration node runs
// its nets for: the engine matches the name, it knows no particular block. Or one value replaced
// by another wherever blocks of a type hold it, e.g. a robot's own controller action in place of
// the ROS default name the nets were written with: the caller names type and property.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "imagenets/property.h"

namespace imagenets {

class Executor;

// Sets `property` (as written text, validated as in a net file) on every block of `exec`'s net and
// of its sub-nets that declares a property of that name and for which `accept` (if given) is true.
// Returns the blocks set, as run-event paths ("samples/predict", "samples/until/solve"). Throws PropertyError / NetError
// naming the block when the text is not a valid value there. As with Executor::setProperty, the
// next run re-runs what changed: the blocks set, the sub-net blocks holding them, their downstream.
std::vector<std::string> setPropertyInNetTree(Executor& exec, const std::string& property, const std::string& text,
                                              const std::function<bool(const PropertySpec&)>& accept = {});

// Replaces the value `from` by `to` in the property `property` of every block of type `block_type`
// ("imagenets/FollowJointTrajectory") in `exec`'s net and its sub-nets that holds `from` (compared
// as values, both texts parsed as the net file's would be); blocks holding another value keep it.
// Returns the blocks changed, as run-event paths. Throws NetError naming the block when `to` is
// not a valid value there (or `from` is not one: no block could hold it). Re-runs as above.
std::vector<std::string> replacePropertyValueInNetTree(Executor& exec, const std::string& block_type,
                                                       const std::string& property, const std::string& from,
                                                       const std::string& to);

}  // namespace imagenets
