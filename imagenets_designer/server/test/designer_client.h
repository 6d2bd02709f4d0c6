// A WebSocket client of the Designer protocol for the tests and the benchmark: connects to
// ws://127.0.0.1:PORT/ws, sends requests, and collects every message the server sends (on its
// own network thread) so a test can wait for a reply, a push or a port-data frame.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

namespace imagenets {
namespace designer {

class DesignerClient {
 public:
  struct Message {
    bool binary = false;
    std::string data;
    std::chrono::steady_clock::time_point received;
    nlohmann::json json;    // text: the message; binary: the port-data header
    std::string payload;    // binary: the payload after the header
  };

  explicit DesignerClient(int port, const std::string& host = "127.0.0.1");
  ~DesignerClient();

  void sendText(const std::string& text);
  void sendBinary(const std::string& data);
  // Sends `request` with a fresh id and returns the reply to it (other messages stay queued).
  nlohmann::json request(nlohmann::json request, double timeout_s = 60);
  // The first queued or arriving message that matches (removed from the queue); throws
  // std::runtime_error after the timeout, naming what it waited for.
  Message waitFor(const std::function<bool(const Message&)>& match, const std::string& what, double timeout_s = 60);
  nlohmann::json waitForText(const std::function<bool(const nlohmann::json&)>& match, const std::string& what,
                             double timeout_s = 60);
  Message waitForFrame(const std::string& port, const std::string& mode, double timeout_s = 60);
  // Drops every queued message.
  void clear();
  // Stops taking messages off the socket (a tab that falls behind) / starts again.
  void pauseReading();
  void resumeReading();
  bool connected() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int next_id_ = 1;
};

}  // namespace designer
}  // namespace imagenets
