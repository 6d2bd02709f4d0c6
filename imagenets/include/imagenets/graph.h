// Draws a net as a Graphviz graph, as the paper's Designer shows it: blocks with their ports,
// ports coloured by data type, links between them, feedback as a dashed edge from the score back
// to the tuned block.
#pragma once

#include <string>

#include "imagenets/net.h"

namespace imagenets {

// A stable colour per data type, the same in every drawing.
std::string typeColor(const std::string& type_name);
// expand_sub_nets: draw each sub-net's blocks inside a cluster beside its SubNet block.
std::string toDot(const Net& net, bool expand_sub_nets = false);
// Runs Graphviz `dot -T<format>` (Debian's graphviz) on DOT text: the picture's bytes ("svg",
// "png", ...). Throws std::runtime_error when dot is missing or fails.
std::string renderDot(const std::string& dot, const std::string& format);

}  // namespace imagenets
