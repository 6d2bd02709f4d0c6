// A net as a launch file (docs/launch.md): every block a nodelet in one manager, properties as
// private parameters, each link a remap of the input `~in/<port>` to the output `<block>/out/<port>`.
#pragma once

#include <string>

#include "imagenets/net.h"

namespace imagenets {
namespace designer {

std::string exportLaunch(const NetSpec& spec);

}  // namespace designer
}  // namespace imagenets
