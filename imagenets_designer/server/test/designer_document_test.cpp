// The net a page edits as a whole: a net opened from a file can be cleared and built anew, each
// opened net is a new document (its state and its port values say which, so nothing shown of one
// net carries over to another), and one block can run alone on its current inputs.
#include "designer_test_util.h"
#include "imagenets/net.h"
#include "imagenets/testing/read_file.h"

using namespace imagenets;
using namespace imagenets::designer;
using nlohmann::json;

namespace {

using imagenets::testing::readFile;

json netState(DesignerClient& c) {
  const json reply = c.request({{"op", "hello"}});
  expectOk(reply);
  return reply["net"];
}

const json& blockOf(const json& net, const std::string& name) {
  for (const auto& b : net["blocks"]) {
    if (b["name"] == name) return b;
  }
  throw std::runtime_error("no block " + name + " in " + net.dump());
}

}  // namespace

TEST_F(DesignerTest, AnOpenedNetClearedOfEveryBlockTakesNewBlocks) {
  start();
  DesignerClient& c = connect();
  const std::string file = copyConfigNet("threshold_demo.yaml");
  expectOk(c.request({{"op", "open"}, {"path", file}}));
  // Positions give the file a `designer:` section that names the blocks about to go.
  expectOk(c.request({{"op", "move_blocks"}, {"positions", {{"source", {0, 0}}, {"threshold", {600, 0}}}}}));
  // A block the file does not have, added beside the ones it has.
  const json added = c.request({{"op", "add_block"}, {"type", "imagenets/GaussianBlur"}});
  expectOk(added);
  EXPECT_EQ(added["name"], "gaussian_blur");
  expectOk(c.request({{"op", "remove_blocks"}, {"names", {"source", "gray", "blur", "threshold", "gaussian_blur"}}}));
  json net = netState(c);
  EXPECT_TRUE(net["blocks"].empty()) << net.dump();
  EXPECT_TRUE(net["links"].empty()) << net.dump();

  // A new net built in its place, with the names the Designer chooses.
  const json source = c.request({{"op", "add_block"}, {"type", "imagenets/ImageFileSource"}, {"position", {0, 0}}});
  expectOk(source);
  EXPECT_EQ(source["name"], "image_file_source");
  expectOk(c.request({{"op", "set_property"}, {"block", "image_file_source"}, {"property", "path"}, {"text", "../images/scene.png"}}));
  expectOk(c.request({{"op", "add_block"}, {"type", "imagenets/Grayscale"}, {"position", {300, 0}}}));
  expectOk(c.request({{"op", "add_link"}, {"from", "image_file_source.image"}, {"to", "grayscale.image"}}));
  const json run = c.request({{"op", "run"}});
  expectOk(run);
  EXPECT_EQ(run["ran"].size(), 2u) << run.dump();

  net = netState(c);  // `hello` still answers (it failed for good before)
  const std::string yaml = net["yaml"];
  expectContains(yaml, "The segmentation front end");  // the net's doc stays
  expectContains(yaml, "image_file_source:\n    type: imagenets/ImageFileSource");
  expectContains(yaml, "positions: {grayscale: [300, 0], image_file_source: [0, 0]}");
  EXPECT_EQ(yaml.find("  threshold:"), std::string::npos) << yaml;  // (the doc says "threshold")

  // Saved, it is the net on screen, and undo goes back through the clearing.
  expectOk(c.request({{"op", "save"}}));
  const NetSpec saved = parseNetText(readFile(file), file, root() + "/nets");
  ASSERT_EQ(saved.blocks.size(), 2u);
  EXPECT_EQ(saved.blocks[0].name, "image_file_source");
  for (int i = 0; i < 4; ++i) expectOk(c.request({{"op", "undo"}}));  // link, gray, path, source
  EXPECT_EQ(netState(c)["blocks"].size(), 0u);
  expectOk(c.request({{"op", "undo"}}));
  EXPECT_EQ(netState(c)["blocks"].size(), 5u);
}

TEST_F(DesignerTest, OpeningANetStartsANewDocumentThatItsPortValuesName) {
  start();
  DesignerClient& c = connect();
  DesignerClient& other = connect();
  const long first = netState(c)["document"];
  const std::string demo = copyConfigNet("threshold_demo.yaml");
  const std::string sweep = copyConfigNet("feedback_threshold.yaml");
  expectOk(c.request({{"op", "open"}, {"path", demo}}));
  const long opened = netState(c)["document"];
  EXPECT_GT(opened, first);
  expectOk(c.request({{"op", "run"}}));
  expectOk(c.request({{"op", "watch"}, {"ports", {"threshold.image"}}}));
  EXPECT_EQ(c.waitForFrame("threshold.image", "preview").json["document"], opened);

  // Edits and runs are the same document; another net (with a block of the same name) is not,
  // and every tab hears so.
  expectOk(c.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", 90}}));
  EXPECT_EQ(netState(c)["document"], opened);
  other.clear();
  expectOk(c.request({{"op", "open"}, {"path", sweep}}));
  const json pushed = other.waitForText(
      [&](const json& j) { return j.value("op", "") == "net" && j.value("file", json()) == json(sweep); }, "the other net's state");
  EXPECT_GT(pushed["document"].get<long>(), opened);
  EXPECT_EQ(blockOf(pushed, "threshold")["stats"]["runs"], 0);
  c.clear();
  expectOk(c.request({{"op", "run"}}));
  expectOk(c.request({{"op", "watch"}, {"ports", {"threshold.image"}}}));
  EXPECT_EQ(c.waitForFrame("threshold.image", "preview").json["document"], pushed["document"]);
  // Undo does not reach back into the net opened before.
  expectContains(failure(c.request({{"op", "undo"}})), "nothing to undo");
}

TEST_F(DesignerTest, RunBlockOnlyRunsOneBlockOnItsCurrentInputs) {
  start(copyConfigNet("threshold_demo.yaml"));
  DesignerClient& c = connect();
  expectOk(c.request({{"op", "auto_run"}, {"on", false}}));
  expectOk(c.request({{"op", "run"}}));
  // The source's path changes, but gray runs on the image it has.
  expectOk(c.request({{"op", "set_property"}, {"block", "source"}, {"property", "path"}, {"text", "../images/marker_sample.png"}}));
  const json only = c.request({{"op", "run_block_only"}, {"block", "gray"}});
  expectOk(only);
  EXPECT_EQ(only["ran"], json::array({"gray"})) << only.dump();
  json net = netState(c);
  EXPECT_EQ(blockOf(net, "source")["stats"]["runs"], 1);
  EXPECT_EQ(blockOf(net, "gray")["stats"]["runs"], 2);
  EXPECT_EQ(blockOf(net, "blur")["stats"]["runs"], 1);
  // What the single run left out of date (the source by its new path, blur after gray) comes on
  // the next run.
  const json next = c.request({{"op", "run"}});
  EXPECT_EQ(next["ran"], json::array({"source", "gray", "blur", "threshold"})) << next.dump();
  // "Run from here" runs the block and its downstream.
  const json from = c.request({{"op", "run_block"}, {"block", "gray"}});
  EXPECT_EQ(from["ran"], json::array({"gray", "blur", "threshold"})) << from.dump();
  expectContains(failure(c.request({{"op", "run_block_only"}, {"block", "grey"}})), "no block named 'grey'");
}
