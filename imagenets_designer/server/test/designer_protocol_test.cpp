// The protocol over a real WebSocket on 127.0.0.1: every bad message gets an error that names
// what is wrong, and the server keeps serving (the same connection answers the next request).
#include "designer_test_util.h"

using namespace imagenets::designer;
using nlohmann::json;

namespace {

json nextError(DesignerClient& c) {
  return c.waitForText([](const json& j) { return j.value("op", "") == "error"; }, "an error message");
}

void expectStillServing(DesignerClient& c) {
  const json reply = c.request({{"op", "registry"}});
  expectOk(reply);
  EXPECT_FALSE(reply["blocks"].empty());
}

}  // namespace

TEST_F(DesignerTest, HelloGivesTheRegistryAndTheNet) {
  start();
  DesignerClient& c = connect();
  const json reply = c.request({{"op", "hello"}});
  expectOk(reply);
  bool grayscale = false;
  for (const auto& b : reply["registry"]["blocks"]) {
    if (b["type"] == "imagenets/Grayscale") {
      grayscale = true;
      EXPECT_EQ(b["category"], "preprocessing");
      EXPECT_EQ(b["inputs"][0]["type"], "sensor_msgs/Image");
    }
  }
  EXPECT_TRUE(grayscale);
  EXPECT_EQ(reply["registry"]["types"]["sensor_msgs/Image"], "#4e79a7");  // imagenets::typeColor
  EXPECT_EQ(reply["net"]["op"], "net");
  EXPECT_TRUE(reply["net"]["blocks"].empty());
  EXPECT_FALSE(reply["net"]["can_undo"]);
}

TEST_F(DesignerTest, BadJsonIsNamedAndTheServerKeepsServing) {
  start();
  DesignerClient& c = connect();
  c.sendText("{\"op\": \"hello\", ");
  expectContains(nextError(c)["error"], "bad JSON");
  c.sendText("{\"op\": \"h\xc3\xa9\xc3\xa9");  // cut after a two-byte character
  expectContains(nextError(c)["error"], "bad JSON");
  expectStillServing(c);
}

TEST_F(DesignerTest, UnknownOpAndMissingFieldsAreNamed) {
  start();
  DesignerClient& c = connect();
  std::string e = failure(c.request({{"op", "frobnicate"}}));
  expectContains(e, "unknown op 'frobnicate'");
  expectContains(e, "add_block");
  e = failure(c.request({{"op", "add_block"}}));
  expectContains(e, "request 'add_block': missing field 'type'");
  e = failure(c.request({{"op", "set_property"}, {"block", 3}, {"property", "x"}, {"text", "1"}}));
  expectContains(e, "field 'block' must be a string");
  c.sendText("[1, 2]");
  expectContains(nextError(c)["error"], "a request is a JSON object");
  expectStillServing(c);
}

TEST_F(DesignerTest, UnknownBlocksAndPortsAreNamed) {
  start();
  DesignerClient& c = connect();
  expectOk(c.request({{"op", "add_block"}, {"type", "imagenets/Grayscale"}, {"name", "gray"}}));
  expectContains(failure(c.request({{"op", "set_property"}, {"block", "grey"}, {"property", "x"}, {"text", "1"}})),
                 "no block named 'grey'");
  expectContains(failure(c.request({{"op", "watch"}, {"ports", {"gray.imag"}}, {"mode", "preview"}})),
                 "block 'gray' has no output port 'imag' (outputs: image [sensor_msgs/Image])");
  expectContains(failure(c.request({{"op", "watch"}, {"ports", {"nope.image"}}})), "no block for output 'nope.image'");
  expectContains(failure(c.request({{"op", "add_link"}, {"from", "gray.image"}, {"to", "gray.colour"}})),
                 "block 'gray' has no input port 'colour'");
  expectContains(failure(c.request({{"op", "add_block"}, {"type", "imagenets/Greyscale"}})),
                 "unknown block type 'imagenets/Greyscale'; did you mean 'imagenets/Grayscale'");
  expectContains(failure(c.request({{"op", "run_block"}, {"block", "blur"}})), "no block named 'blur'");
  expectStillServing(c);
}

TEST_F(DesignerTest, HugeMessageIsRefusedAndTheConnectionStays) {
  start();
  DesignerClient& c = connect();
  c.sendText(std::string(5 * 1024 * 1024, ' '));
  const std::string e = nextError(c)["error"];
  expectContains(e, "is too large");
  expectContains(e, "4194304");
  expectStillServing(c);
}

TEST_F(DesignerTest, BinaryMessageIsRefusedAndTheConnectionStays) {
  start();
  DesignerClient& c = connect();
  c.sendBinary(std::string("\x01\x02\x03", 3));
  expectContains(nextError(c)["error"], "binary message refused");
  expectStillServing(c);
}

TEST_F(DesignerTest, PathsOutsideTheRootsAreRefused) {
  start();
  DesignerClient& c = connect();
  std::string e = failure(c.request({{"op", "open"}, {"path", "/etc/passwd"}}));
  expectContains(e, "path '/etc/passwd' is outside the allowed folders");
  expectContains(e, root());
  expectOk(c.request({{"op", "add_block"}, {"type", "imagenets/Grayscale"}}));
  e = failure(c.request({{"op", "save"}, {"path", root() + "/../escaped.yaml"}}));
  expectContains(e, "is outside the allowed folders");
  EXPECT_FALSE(boost::filesystem::exists(root_.parent_path() / "escaped.yaml"));
  expectContains(failure(c.request({{"op", "list_files"}, {"dir", "/"}})), "path '/' is outside the allowed folders");
  // A symbolic link inside a root does not lead out of it.
  boost::filesystem::create_directory_symlink("/etc", root_ / "etc");
  expectContains(failure(c.request({{"op", "open"}, {"path", root() + "/etc/hostname"}})), "outside the allowed folders");
  expectStillServing(c);
}

TEST_F(DesignerTest, ServesThePageOverHttp) {
  start();
  namespace http = boost::beast::http;
  const auto res = httpGet(server_->port(), "/");
  EXPECT_EQ(res.result(), http::status::ok);
  expectContains(res.body(), "<html");
  expectContains(std::string(res[http::field::content_type]), "text/html");
  // The icon a browser asks for by itself is no error (the page's icon, or nothing when the page
  // is not built).
  const auto icon = httpGet(server_->port(), "/favicon.ico");
  EXPECT_TRUE(icon.result() == http::status::ok || icon.result() == http::status::no_content) << icon.result();
  if (icon.result() == http::status::ok) {
    EXPECT_EQ(std::string(icon[http::field::content_type]), "image/svg+xml");
    expectContains(icon.body(), "<svg");
  }
  EXPECT_EQ(httpGet(server_->port(), "/nothing.here").result(), http::status::not_found);
}
