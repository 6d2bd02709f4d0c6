// One HTTP connection: serves the built page (static files under the web root, `/` ->
// index.html) and hands a WebSocket upgrade of `/ws` to a WebSocketConnection.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "beast.h"

namespace imagenets {
namespace designer {

class HttpConnection : public std::enable_shared_from_this<HttpConnection> {
 public:
  using Upgrade = std::function<void(tcp::socket, http::request<http::string_body>)>;
  HttpConnection(tcp::socket socket, std::string web_root, Upgrade upgrade);
  void start();

 private:
  void read();
  void respond();

  beast::tcp_stream stream_;
  std::string web_root_;
  Upgrade upgrade_;
  beast::flat_buffer buffer_;
  http::request<http::string_body> request_;
};

}  // namespace designer
}  // namespace imagenets
