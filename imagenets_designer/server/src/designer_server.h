// The Designer's server: HTTP for the page and a WebSocket at /ws for the protocol
// (designer/PROTOCOL.md). One network thread; requests run one at a time on a worker thread
// against one DesignerSession, which every connected tab shares.
//
//   imagenets::designer::DesignerServer server(options);
//   server.start();                 // binds (127.0.0.1 by default); throws naming the address
//   std::cout << server.url();
//   DesignerServer::waitForSignal();  // SIGINT / SIGTERM (blockStopSignals() first)
#pragma once

#include <memory>
#include <string>

#include "designer_session.h"

namespace imagenets {
namespace designer {

class DesignerServer {
 public:
  struct Options {
    std::string bind = "127.0.0.1";
    int port = 8080;       // 0: any free port (tests)
    std::string web_root;  // the built page (designer/web/dist); empty: a note that it is not built
    DesignerSession::Options session;
  };

  explicit DesignerServer(Options options);
  ~DesignerServer();

  DesignerSession& session();  // before start() only (e.g. openStartupNet)
  void start();
  int port() const;
  std::string url() const;
  void stop();
  // Call blockStopSignals() before any thread starts (so no thread dies of SIGINT), then
  // waitForSignal() returns on SIGINT or SIGTERM.
  static void blockStopSignals();
  static void waitForSignal();

  // The built page: designer/web/dist in the source tree, else the installed share folder.
  static std::string findWebRoot();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace designer
}  // namespace imagenets
