// `imagenets designer [NET] [--port 8080] [--bind 127.0.0.1] [--root DIR]...`: serves the
// ImageNet Designer (paper 3.2) on the in-process executor; open the printed address in a browser.
#include <iostream>

#include <boost/filesystem.hpp>

#include "imagenets/tool/command.h"
#include "designer_server.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace tool {
namespace {

int run(const Args& args) {
  designer::DesignerServer::Options options;
  std::string net;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--port") {
      options.port = intValue(args, i);
      if (options.port < 0 || options.port > 65535) {
        throw UsageError("--port " + std::to_string(options.port) + " is out of range 0..65535");
      }
    } else if (args[i] == "--bind") {
      options.bind = flagValue(args, i);
    } else if (args[i] == "--root") {
      const std::string dir = flagValue(args, i);
      if (!boost::filesystem::is_directory(dir)) throw UsageError("--root '" + dir + "' is not a folder");
      options.session.roots.push_back(dir);
    } else if (args[i].rfind("__", 0) == 0) {
      continue;  // roslaunch's __name:= / __log:=
    } else if (net.empty() && !(args[i].size() > 1 && args[i][0] == '-')) {
      net = args[i];
    } else {
      throw unknownArgument(args[i]);
    }
  }
  // Without a net or a root, new nets are saved in the working folder.
  if (net.empty() && options.session.roots.empty()) options.session.roots.push_back(boost::filesystem::current_path().string());
  BlockRegistry::instance().loadLibraries();  // every block library installed, for the block browser
  options.web_root = designer::DesignerServer::findWebRoot();

  designer::DesignerServer::blockStopSignals();
  designer::DesignerServer server(options);
  if (!net.empty() && !server.session().openStartupNet(net)) {
    std::cerr << "imagenets designer: " << net << " does not load; the Designer starts with an empty net:\n";
    for (const auto& e : server.session().netState()["errors"]) std::cerr << "  " << e.get<std::string>() << "\n";
  }
  server.start();
  std::cout << "ImageNet Designer: " << server.url() << (options.web_root.empty() ? " (no page: imagenets_designer/web/dist not found; source the workspace's setup.bash, or build it)" : "")
            << "\nallowed folders:";
  for (const auto& r : server.session().roots().roots()) std::cout << " " << r;
  std::cout << "\nCtrl+C stops it." << std::endl;
  designer::DesignerServer::waitForSignal();
  std::cout << "stopping" << std::endl;
  server.stop();
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(designer, "designer", "designer [NET] [--port 8080] [--bind 127.0.0.1] [--root DIR]...",
                       "serve the ImageNet Designer (web page: build, run and inspect nets) on the in-process executor",
                       run);

}  // namespace tool
}  // namespace imagenets
