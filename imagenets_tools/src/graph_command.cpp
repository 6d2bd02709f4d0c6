// `imagenets graph NET -o FILE.svg`: draws the net with Graphviz (Debian's `graphviz`).
#include <cstdio>
#include <fstream>
#include <iostream>

#include "imagenets/tool/command.h"
#include "imagenets/graph.h"

namespace imagenets {
namespace tool {
namespace {

void declare(Flags& f) {
  f.add()("output,o", po::value<std::string>(), "the picture: FILE.svg, FILE.png or FILE.dot")
      ("expand", po::bool_switch(), "draw sub-nets inside their blocks");
  f.operand("NET", 1, "the net file");
}

int run(const Options& o) {
  const auto nets = strings(o, "NET");
  const std::string out = stringFlag(o, "output");
  if (nets.empty() || out.empty()) throw UsageError("expects a net file and -o FILE");
  const std::string dot = toDot(*Net::loadFile(nets.front()), o["expand"].as<bool>());
  const auto ext_pos = out.rfind('.');
  const std::string format = ext_pos == std::string::npos ? "svg" : out.substr(ext_pos + 1);
  if (format == "dot") {
    std::ofstream(out) << dot;
  } else {
    const std::string picture = renderDot(dot, format);
    const std::string tmp = out + ".tmp";
    std::ofstream(tmp, std::ios::binary) << picture;
    std::rename(tmp.c_str(), out.c_str());
  }
  std::cout << "wrote " << out << "\n";
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(graph, "graph", "graph NET -o FILE.svg|.png|.dot [--expand]",
                       "draw the net: blocks, ports coloured by data type, links, feedback; --expand draws sub-nets inside", declare, run);

}  // namespace tool
}  // namespace imagenets
