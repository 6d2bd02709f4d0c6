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

void declare(Flags& f) {
  const designer::DesignerServer::Options defaults;
  f.add()("port", po::value<int>()->default_value(defaults.port), "the HTTP port (0: any free one)")
      ("bind", po::value<std::string>()->default_value(defaults.bind), "the address to listen on")
      ("root", po::value<std::vector<std::string>>(), "a folder nets may be opened from and saved to (repeatable)");
  f.operand("NET", 1, "the net to open");
  f.acceptRosArguments();
}

int run(const Options& o) {
  designer::DesignerServer::Options options;
  options.port = o["port"].as<int>();
  if (options.port < 0 || options.port > 65535) {
    throw UsageError("--port " + std::to_string(options.port) + " is out of range 0..65535");
  }
  options.bind = o["bind"].as<std::string>();
  for (const auto& dir : strings(o, "root")) {
    if (!boost::filesystem::is_directory(dir)) throw UsageError("--root '" + dir + "' is not a folder");
    options.session.roots.push_back(dir);
  }
  const auto nets = strings(o, "NET");
  const std::string net = nets.empty() ? std::string() : nets.front();
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
                       declare, run);

}  // namespace tool
}  // namespace imagenets
