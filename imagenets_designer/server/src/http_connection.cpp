#include "http_connection.h"

#include <chrono>
#include <fstream>
#include <iterator>

#include <boost/filesystem.hpp>

namespace imagenets {
namespace designer {

namespace {

std::string mimeType(const std::string& path) {
  const auto ext = boost::filesystem::path(path).extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json" || ext == ".map") return "application/json";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".ico") return "image/x-icon";
  if (ext == ".woff2") return "font/woff2";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

const char* kNoPage =
    "<!doctype html><html><head><title>ImageNet Designer</title></head><body>"
    "<h1>ImageNet Designer</h1><p>The server runs, but the page is not built: run <code>make</code> "
    "(it builds designer/web with npm). The WebSocket API is at <code>/ws</code> "
    "(designer/PROTOCOL.md).</p></body></html>";

}  // namespace

HttpConnection::HttpConnection(tcp::socket socket, std::string web_root, Upgrade upgrade)
    : stream_(std::move(socket)), web_root_(std::move(web_root)), upgrade_(std::move(upgrade)) {}

void HttpConnection::start() { read(); }

void HttpConnection::read() {
  request_ = {};
  stream_.expires_after(std::chrono::seconds(60));
  http::async_read(stream_, buffer_, request_, [self = shared_from_this()](beast::error_code ec, size_t) {
    if (ec) return;
    self->respond();
  });
}

void HttpConnection::respond() {
  if (websocket::is_upgrade(request_)) {
    if (request_.target() == "/ws") {
      stream_.expires_never();
      upgrade_(stream_.release_socket(), std::move(request_));
      return;
    }
  }
  auto res = std::make_shared<http::response<http::string_body>>();
  res->version(request_.version());
  res->keep_alive(request_.keep_alive());
  res->set(http::field::server, "imagenets-designer");
  std::string target(request_.target());
  target = target.substr(0, target.find_first_of("?#"));
  namespace fs = boost::filesystem;
  auto finish = [&](http::status status, const std::string& type, std::string body) {
    res->result(status);
    res->set(http::field::content_type, type);
    res->set(http::field::cache_control, "no-cache");
    res->body() = request_.method() == http::verb::head ? std::string() : std::move(body);
    res->prepare_payload();
  };
  if (request_.method() != http::verb::get && request_.method() != http::verb::head) {
    finish(http::status::method_not_allowed, "text/plain", "only GET\n");
  } else if (target.find("..") != std::string::npos || target.empty() || target[0] != '/') {
    finish(http::status::bad_request, "text/plain", "bad path\n");
  } else {
    if (target == "/") target = "/index.html";
    // Browsers ask for /favicon.ico whatever the page links: the page's SVG icon answers it.
    if (target == "/favicon.ico" && !fs::is_regular_file(fs::path(web_root_) / target)) target = "/favicon.svg";
    const fs::path file = fs::path(web_root_) / target;
    if (!web_root_.empty() && fs::is_regular_file(file)) {
      std::ifstream in(file.string(), std::ios::binary);
      std::string body((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      finish(http::status::ok, mimeType(file.string()), std::move(body));
    } else if (target == "/index.html") {
      finish(http::status::ok, "text/html; charset=utf-8", kNoPage);
    } else if (target == "/favicon.svg") {
      finish(http::status::no_content, "text/plain", "");  // the page is not built: no icon, no error
    } else {
      finish(http::status::not_found, "text/plain", "not found: " + target + "\n");
    }
  }
  http::async_write(stream_, *res, [self = shared_from_this(), res](beast::error_code ec, size_t) {
    if (ec || !res->keep_alive()) {
      beast::error_code ignored;
      self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      return;
    }
    self->read();
  });
}

}  // namespace designer
}  // namespace imagenets
