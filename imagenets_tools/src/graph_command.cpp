// `imagenets graph NET -o FILE.svg`: draws the net with Graphviz (Debian's `graphviz`).
#include <cstdio>
#include <fstream>
#include <iostream>

#include "imagenets/tool/command.h"
#include "imagenets/graph.h"

namespace imagenets {
namespace tool {
namespace {

int run(const Args& args) {
  std::string net_path, out;
  bool expand = false;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "-o" || args[i] == "--output") out = flagValue(args, i);
    else if (args[i] == "--expand") expand = true;
    else if (net_path.empty() && !(args[i].size() > 1 && args[i][0] == '-')) net_path = args[i];
    else throw unknownArgument(args[i]);
  }
  if (net_path.empty() || out.empty()) throw UsageError("expects a net file and -o FILE");
  const std::string dot = toDot(*Net::loadFile(net_path), expand);
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
                       "draw the net: blocks, ports coloured by data type, links, feedback; --expand draws sub-nets inside", run);

}  // namespace tool
}  // namespace imagenets
