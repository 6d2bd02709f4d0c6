// What the Designer's tests share: a server on a free port of 127.0.0.1 with a temporary folder
// as its allowed root, and clients connected to it.
#pragma once

#include <memory>
#include <string>

#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "designer_client.h"
#include "designer_server.h"

namespace imagenets {
namespace designer {

const std::string kSourceDir = IMAGENETS_SOURCE_DIR;

class DesignerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = boost::filesystem::temp_directory_path() / boost::filesystem::unique_path("designer-test-%%%%-%%%%");
    boost::filesystem::create_directories(root_);
  }
  void TearDown() override {
    clients_.clear();
    server_.reset();
    boost::filesystem::remove_all(root_);
  }
  // Starts the server (with `net` opened, if given).
  void start(const std::string& net = "") {
    DesignerServer::Options options;
    options.port = 0;
    options.session.roots = {root_.string()};
    server_ = std::make_unique<DesignerServer>(options);
    if (!net.empty()) ASSERT_TRUE(server_->session().openStartupNet(net)) << net;
    server_->start();
  }
  DesignerClient& connect() {
    clients_.push_back(std::make_unique<DesignerClient>(server_->port()));
    return *clients_.back();
  }
  std::string root() const { return root_.string(); }
  // A copy of a net of config/nets in the root, with the folders it refers to (../images, ...)
  // linked beside it, so it can be opened and saved in place.
  std::string copyConfigNet(const std::string& name) {
    namespace fs = boost::filesystem;
    fs::create_directories(root_ / "nets");
    for (const char* dir : {"images", "cameras", "markers", "friend"}) {
      // symlink_status: a link made by an earlier call may point at a folder this checkout lacks.
      if (!fs::exists(fs::symlink_status(root_ / dir))) fs::create_directory_symlink(fs::path(kSourceDir) / "config" / dir, root_ / dir);
    }
    const fs::path target = root_ / "nets" / name;
    fs::copy_file(fs::path(kSourceDir) / "config" / "nets" / name, target);
    return target.string();
  }

  boost::filesystem::path root_;
  std::unique_ptr<DesignerServer> server_;
  std::vector<std::unique_ptr<DesignerClient>> clients_;
};

inline void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in:\n" << text;
}

// A reply that failed, with its error text.
inline std::string failure(const nlohmann::json& reply) {
  EXPECT_FALSE(reply.value("ok", true)) << reply.dump();
  return reply.value("error", std::string());
}

inline void expectOk(const nlohmann::json& reply) { EXPECT_TRUE(reply.value("ok", false)) << reply.dump(); }

// GET `target` from the server on 127.0.0.1:port.
inline boost::beast::http::response<boost::beast::http::string_body> httpGet(int port, const std::string& target) {
  namespace beast = boost::beast;
  namespace http = beast::http;
  boost::asio::io_context ioc;
  beast::tcp_stream stream(ioc);
  stream.connect(boost::asio::ip::tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  http::request<http::string_body> req{http::verb::get, target, 11};
  req.set(http::field::host, "127.0.0.1");
  http::write(stream, req);
  beast::flat_buffer buffer;
  http::response<http::string_body> res;
  http::read(stream, buffer, res);
  return res;
}

}  // namespace designer
}  // namespace imagenets
