// Text inside XML (plug-in descriptions, Graphviz HTML labels, launch files): < > & " escaped.
#pragma once

#include <string>

namespace imagenets {

std::string xmlEscape(const std::string& text);

}  // namespace imagenets
