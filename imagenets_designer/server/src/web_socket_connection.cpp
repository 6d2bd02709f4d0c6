#include "web_socket_connection.h"

#include "net_state_json.h"

namespace imagenets {
namespace designer {

WebSocketConnection::WebSocketConnection(tcp::socket socket, int id, Hub& hub)
    : ws_(std::move(socket)), id_(id), hub_(hub) {}

void WebSocketConnection::accept(http::request<http::string_body> request) {
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  // A preview (up to 147 kB of pixels) goes out as one frame: Beast's default cuts a message into
  // 4 kB frames, each its own write, and the page waited for the last of ~36.
  ws_.auto_fragment(false);
  ws_.read_message_max(0);  // sizes are checked per message below, so an oversized one is skipped, not fatal
  ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
    if (ec) return;
    self->hub_.opened(self);
    self->read();
  });
}

void WebSocketConnection::read() {
  ws_.async_read_some(buffer_, 64 * 1024,
                      [self = shared_from_this()](beast::error_code ec, size_t bytes) { self->onRead(ec, bytes); });
}

void WebSocketConnection::onRead(beast::error_code ec, size_t bytes) {
  if (ec) {
    if (!closed_) {
      closed_ = true;
      hub_.closed(id_);
    }
    return;
  }
  message_bytes_ += bytes;
  if (message_bytes_ > kMaxMessageBytes) buffer_.clear();  // keep reading to the message's end, keep nothing
  if (ws_.is_message_done()) {
    if (message_bytes_ > kMaxMessageBytes) {
      error("message of " + std::to_string(message_bytes_) + " bytes is too large (the limit is " +
            std::to_string(kMaxMessageBytes) + " bytes)");
    } else if (ws_.got_binary()) {
      error("binary message refused: requests are JSON text frames");
    } else {
      hub_.received(id_, beast::buffers_to_string(buffer_.data()));
    }
    buffer_.clear();
    message_bytes_ = 0;
  }
  read();
}

void WebSocketConnection::error(const std::string& message) {
  sendText(std::make_shared<const std::string>(jsonText({{"op", "error"}, {"error", message}})));
}

void WebSocketConnection::sendText(std::shared_ptr<const std::string> text) {
  if (closed_) return;
  texts_.push_back(std::move(text));
  write();
}

void WebSocketConnection::sendPortData(const std::string& slot, std::shared_ptr<const std::string> frame) {
  if (closed_) return;
  auto it = port_data_.find(slot);
  if (it == port_data_.end()) port_order_.push_back(slot);
  port_data_[slot] = std::move(frame);  // an unsent older value of the slot is dropped
  write();
}

void WebSocketConnection::close() {
  if (closed_) return;
  ws_.async_close(websocket::close_code::going_away, [self = shared_from_this()](beast::error_code) {});
}

void WebSocketConnection::write() {
  if (writing_ || closed_) return;
  bool text = true;
  if (!texts_.empty()) {
    writing_ = texts_.front();
    texts_.pop_front();
  } else if (!port_order_.empty()) {
    const std::string slot = port_order_.front();
    port_order_.pop_front();
    writing_ = port_data_[slot];
    port_data_.erase(slot);
    text = false;
  } else {
    return;
  }
  ws_.text(text);
  ws_.async_write(asio::buffer(*writing_), [self = shared_from_this()](beast::error_code ec, size_t) {
    self->writing_.reset();
    if (ec) {
      if (!self->closed_) {
        self->closed_ = true;
        self->hub_.closed(self->id_);
      }
      return;
    }
    self->write();
  });
}

}  // namespace designer
}  // namespace imagenets
