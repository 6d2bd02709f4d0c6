#include "designer_client.h"

#include <future>
#include <thread>

#include "beast.h"
#include "port_data.h"

namespace imagenets {
namespace designer {

struct DesignerClient::Impl {
  asio::io_context ioc;
  // Keeps the network thread alive while no read is armed (reading paused).
  asio::executor_work_guard<asio::io_context::executor_type> work = asio::make_work_guard(ioc);
  websocket::stream<beast::tcp_stream> ws{ioc};
  beast::flat_buffer buffer;
  std::thread thread;
  std::mutex mutex;
  std::condition_variable arrived;
  std::deque<Message> queue;
  std::deque<std::pair<bool, std::shared_ptr<std::string>>> outgoing;
  bool writing = false;
  bool open = false;
  bool paused = false;   // network thread only
  bool reading = false;  // network thread only

  void read() {
    reading = true;
    ws.async_read(buffer, [this](beast::error_code ec, size_t) {
      reading = false;
      if (ec) {
        std::lock_guard<std::mutex> lock(mutex);
        open = false;
        arrived.notify_all();
        return;
      }
      Message m;
      m.binary = ws.got_binary();
      m.data = beast::buffers_to_string(buffer.data());
      m.received = std::chrono::steady_clock::now();
      buffer.clear();
      if (m.binary) decodePortFrame(m.data, m.json, m.payload);
      else m.json = nlohmann::json::parse(m.data, nullptr, false);
      {
        std::lock_guard<std::mutex> lock(mutex);
        queue.push_back(std::move(m));
      }
      arrived.notify_all();
      if (!paused) read();
    });
  }

  void write() {
    if (writing || outgoing.empty()) return;
    writing = true;
    auto next = outgoing.front();
    outgoing.pop_front();
    ws.binary(next.first);
    ws.async_write(asio::buffer(*next.second), [this, next](beast::error_code, size_t) {
      writing = false;
      write();
    });
  }

  void send(bool binary, std::string data) {
    auto shared = std::make_shared<std::string>(std::move(data));
    asio::post(ioc, [this, binary, shared] {
      outgoing.emplace_back(binary, shared);
      write();
    });
  }
};

DesignerClient::DesignerClient(int port, const std::string& host) : impl_(std::make_unique<Impl>()) {
  tcp::resolver resolver(impl_->ioc);
  auto endpoints = resolver.resolve(host, std::to_string(port));
  beast::get_lowest_layer(impl_->ws).connect(endpoints);
  beast::get_lowest_layer(impl_->ws).socket().set_option(tcp::no_delay(true));
  impl_->ws.read_message_max(0);
  impl_->ws.handshake(host + ":" + std::to_string(port), "/ws");
  impl_->open = true;
  impl_->read();
  impl_->thread = std::thread([this] { impl_->ioc.run(); });
}

DesignerClient::~DesignerClient() {
  asio::post(impl_->ioc, [this] {
    beast::error_code ec;
    beast::get_lowest_layer(impl_->ws).socket().shutdown(tcp::socket::shutdown_both, ec);
    beast::get_lowest_layer(impl_->ws).close();
    impl_->work.reset();
  });
  impl_->thread.join();
}

bool DesignerClient::connected() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->open;
}

void DesignerClient::sendText(const std::string& text) { impl_->send(false, text); }
void DesignerClient::sendBinary(const std::string& data) { impl_->send(true, data); }

DesignerClient::Message DesignerClient::waitFor(const std::function<bool(const Message&)>& match, const std::string& what,
                                                double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::unique_lock<std::mutex> lock(impl_->mutex);
  size_t checked = 0;
  for (;;) {
    for (; checked < impl_->queue.size(); ++checked) {
      if (match(impl_->queue[checked])) {
        Message m = std::move(impl_->queue[checked]);
        impl_->queue.erase(impl_->queue.begin() + static_cast<long>(checked));
        return m;
      }
    }
    if (!impl_->open) throw std::runtime_error("connection closed while waiting for " + what);
    if (impl_->arrived.wait_until(lock, deadline) == std::cv_status::timeout && checked == impl_->queue.size()) {
      throw std::runtime_error("timed out waiting for " + what);
    }
  }
}

nlohmann::json DesignerClient::waitForText(const std::function<bool(const nlohmann::json&)>& match,
                                           const std::string& what, double timeout_s) {
  return waitFor([&](const Message& m) { return !m.binary && match(m.json); }, what, timeout_s).json;
}

DesignerClient::Message DesignerClient::waitForFrame(const std::string& port, const std::string& mode,
                                                     double timeout_s) {
  return waitFor(
      [&](const Message& m) { return m.binary && m.json.value("port", "") == port && m.json.value("mode", "") == mode; },
      "a " + mode + " frame of " + port, timeout_s);
}

nlohmann::json DesignerClient::request(nlohmann::json request, double timeout_s) {
  const int id = next_id_++;
  request["id"] = id;
  sendText(request.dump());
  return waitForText([id](const nlohmann::json& j) { return j.value("op", "") == "reply" && j.contains("id") && j["id"] == id; },
                     "the reply to " + request.value("op", std::string("?")), timeout_s);
}

void DesignerClient::pauseReading() {
  std::promise<void> done;
  asio::post(impl_->ioc, [this, &done] {
    impl_->paused = true;
    done.set_value();
  });
  done.get_future().wait();
}

void DesignerClient::resumeReading() {
  asio::post(impl_->ioc, [this] {
    impl_->paused = false;
    if (!impl_->reading) impl_->read();
  });
}

void DesignerClient::clear() {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->queue.clear();
}

}  // namespace designer
}  // namespace imagenets
