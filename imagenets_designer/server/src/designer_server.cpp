#include "designer_server.h"

#include <atomic>
#include <csignal>
#include <map>
#include <thread>

#include <boost/filesystem.hpp>
#include <ros/package.h>

#include "beast.h"
#include "http_connection.h"
#include "net_state_json.h"
#include "serial_worker.h"
#include "web_socket_connection.h"

namespace imagenets {
namespace designer {

struct DesignerServer::Impl : DesignerSession::Output, WebSocketConnection::Hub {
  explicit Impl(Options o) : options(std::move(o)), acceptor(ioc), session(*this, options.session) {}

  // DesignerSession::Output: from any thread, handed to the network thread.
  void send(int client, const std::string& text) override {
    auto shared = std::make_shared<const std::string>(text);
    asio::post(ioc, [this, client, shared] {
      auto it = connections.find(client);
      if (it != connections.end()) it->second->sendText(shared);
    });
  }
  void broadcast(const std::string& text) override {
    auto shared = std::make_shared<const std::string>(text);
    asio::post(ioc, [this, shared] {
      for (auto& kv : connections) kv.second->sendText(shared);
    });
  }
  void sendPortData(int client, const std::string& slot, std::shared_ptr<const std::string> frame) override {
    asio::post(ioc, [this, client, slot, frame] {
      auto it = connections.find(client);
      if (it != connections.end()) it->second->sendPortData(slot, frame);
    });
  }

  // WebSocketConnection::Hub: on the network thread.
  void opened(const std::shared_ptr<WebSocketConnection>& connection) override {
    connections[connection->id()] = connection;
  }
  void received(int id, std::string text) override {
    nlohmann::json request;
    try {
      request = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
      send(id, jsonText({{"op", "error"}, {"error", std::string("bad JSON: ") + e.what()}}));
      return;
    }
    // Cancel cannot wait behind the run it is meant to stop.
    if (request.is_object() && request.value("op", nlohmann::json()) == "cancel") {
      session.cancel();
      send(id, jsonText({{"op", "reply"}, {"id", request.value("id", nlohmann::json())}, {"ok", true}}));
      return;
    }
    worker.post([this, id, request = std::move(request)] { session.handle(id, request); });
  }
  void closed(int id) override {
    connections.erase(id);
    worker.post([this, id] { session.disconnected(id); });
  }

  void accept() {
    acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
      if (ec) return;  // stopped
      // Small frames (a reply, then a preview) must not wait for the previous one's ACK (Nagle).
      socket.set_option(tcp::no_delay(true), ec);
      auto upgrade = [this](tcp::socket s, http::request<http::string_body> request) {
        auto ws = std::make_shared<WebSocketConnection>(std::move(s), ++next_id, *this);
        ws->accept(std::move(request));
      };
      std::make_shared<HttpConnection>(std::move(socket), options.web_root, upgrade)->start();
      accept();
    });
  }

  Options options;
  asio::io_context ioc;
  tcp::acceptor acceptor;
  DesignerSession session;
  SerialWorker worker;  // after session: destroyed first, so queued requests finish against it
  std::map<int, std::shared_ptr<WebSocketConnection>> connections;
  int next_id = 0;
  std::thread thread;
  std::atomic<bool> stopped{false};
};

DesignerServer::DesignerServer(Options options) : impl_(std::make_unique<Impl>(std::move(options))) {}

DesignerServer::~DesignerServer() { stop(); }

DesignerSession& DesignerServer::session() { return impl_->session; }

void DesignerServer::start() {
  auto& i = *impl_;
  beast::error_code ec;
  const auto address = asio::ip::make_address(i.options.bind, ec);
  if (ec) throw std::runtime_error("--bind '" + i.options.bind + "' is not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(i.options.port));
  i.acceptor.open(endpoint.protocol());
  i.acceptor.set_option(asio::socket_base::reuse_address(true));
  i.acceptor.bind(endpoint, ec);
  if (ec) {
    throw std::runtime_error("cannot listen on " + i.options.bind + ":" + std::to_string(i.options.port) + ": " +
                             ec.message());
  }
  i.acceptor.listen();
  i.accept();
  i.thread = std::thread([&i] { i.ioc.run(); });
}

int DesignerServer::port() const { return impl_->acceptor.local_endpoint().port(); }

std::string DesignerServer::url() const {
  return "http://" + impl_->options.bind + ":" + std::to_string(port()) + "/";
}

void DesignerServer::stop() {
  auto& i = *impl_;
  if (i.stopped.exchange(true)) return;
  i.session.cancel();
  i.ioc.stop();
  if (i.thread.joinable()) i.thread.join();
}

namespace {
sigset_t stopSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}
}  // namespace

void DesignerServer::blockStopSignals() {
  const sigset_t set = stopSignals();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
}

void DesignerServer::waitForSignal() {
  const sigset_t set = stopSignals();
  int signal = 0;
  sigwait(&set, &signal);
}

std::string DesignerServer::findWebRoot() {
  namespace fs = boost::filesystem;
  // The package's folder: the source tree (web/dist is built there) or the install space.
  const std::string package = ros::package::getPath("imagenets_designer");
  if (package.empty()) return "";
  const fs::path dist = fs::path(package) / "web" / "dist";
  return fs::is_regular_file(dist / "index.html") ? dist.string() : "";
}

}  // namespace designer
}  // namespace imagenets
