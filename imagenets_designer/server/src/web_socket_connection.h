// One browser tab's WebSocket. Text frames from the tab go to the hub one message at a time;
// messages over the size limit are read to their end and discarded (the tab gets an error, the
// connection stays). Outgoing text is sent in order; port data is kept per slot, newest only, so
// a tab that falls behind skips stale values instead of queueing them.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <string>

#include "beast.h"

namespace imagenets {
namespace designer {

constexpr size_t kMaxMessageBytes = 4 * 1024 * 1024;

class WebSocketConnection : public std::enable_shared_from_this<WebSocketConnection> {
 public:
  class Hub {
   public:
    virtual ~Hub() = default;
    virtual void opened(const std::shared_ptr<WebSocketConnection>& connection) = 0;
    virtual void received(int id, std::string text) = 0;
    virtual void closed(int id) = 0;
  };

  WebSocketConnection(tcp::socket socket, int id, Hub& hub);
  void accept(http::request<http::string_body> request);
  int id() const { return id_; }

  // Network thread only.
  void sendText(std::shared_ptr<const std::string> text);
  void sendPortData(const std::string& slot, std::shared_ptr<const std::string> frame);
  void close();

 private:
  void read();
  void onRead(beast::error_code ec, size_t bytes);
  void error(const std::string& message);
  void write();

  websocket::stream<beast::tcp_stream> ws_;
  int id_;
  Hub& hub_;
  beast::flat_buffer buffer_;
  size_t message_bytes_ = 0;
  bool closed_ = false;
  std::deque<std::shared_ptr<const std::string>> texts_;
  std::map<std::string, std::shared_ptr<const std::string>> port_data_;
  std::deque<std::string> port_order_;
  std::shared_ptr<const std::string> writing_;
};

}  // namespace designer
}  // namespace imagenets
