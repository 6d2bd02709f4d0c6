// Editing a net through the protocol: the engine validates every edit (a refused one changes
// nothing), undo/redo, incremental re-runs after a property change, several tabs on one net,
// saving (the file loads as the same net; an unchanged hand-written net keeps its text).
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "designer_test_util.h"
#include "imagenets/executor.h"
#include "imagenets/net_writer.h"
#include "imagenets/registry.h"
#include "imagenets/package_file.h"
#include "imagenets/testing/read_file.h"

using namespace imagenets;
using namespace imagenets::designer;
using nlohmann::json;

namespace {

using imagenets::testing::readFile;

json addBlock(DesignerClient& c, const std::string& type, const std::string& name) {
  json reply = c.request({{"op", "add_block"}, {"type", type}, {"name", name}, {"position", {10, 20}}});
  expectOk(reply);
  return reply;
}

// ImageFileSource -> Grayscale -> Threshold on the 1024x768 scene.
void buildChain(DesignerClient& c) {
  addBlock(c, "imagenets/ImageFileSource", "source");
  expectOk(c.request({{"op", "set_property"}, {"block", "source"}, {"property", "path"},
                      {"text", kSourceDir + "/config/images/scene.png"}}));
  addBlock(c, "imagenets/Grayscale", "gray");
  addBlock(c, "imagenets/Threshold", "threshold");
  expectOk(c.request({{"op", "add_link"}, {"from", "source.image"}, {"to", "gray.image"}}));
  expectOk(c.request({{"op", "add_link"}, {"from", "gray.image"}, {"to", "threshold.image"}}));
}

const json& blockOf(const json& net, const std::string& name) {
  for (const auto& b : net["blocks"]) {
    if (b["name"] == name) return b;
  }
  throw std::runtime_error("no block " + name + " in " + net.dump());
}

json netState(DesignerClient& c) { return c.request({{"op", "hello"}})["net"]; }

}  // namespace

TEST_F(DesignerTest, LinkBetweenDifferentTypesIsRefusedWithTheEnginesMessage) {
  start();
  DesignerClient& c = connect();
  addBlock(c, "imagenets/Grayscale", "gray");
  addBlock(c, "imagenets/CameraInfoFile", "camera");
  const long revision = netState(c)["revision"];
  const std::string e = failure(c.request({{"op", "add_link"}, {"from", "camera.camera_info"}, {"to", "gray.image"}}));
  expectContains(e, "link camera.camera_info -> gray.image: type mismatch: output is sensor_msgs/CameraInfo, input is sensor_msgs/Image");
  const json net = netState(c);
  EXPECT_EQ(net["revision"], revision);
  EXPECT_TRUE(net["links"].empty());
}

TEST_F(DesignerTest, UndoAndRedoStepThroughTheEdits) {
  start();
  DesignerClient& c = connect();
  addBlock(c, "imagenets/Grayscale", "gray");
  addBlock(c, "imagenets/Threshold", "threshold");
  expectOk(c.request({{"op", "add_link"}, {"from", "gray.image"}, {"to", "threshold.image"}}));
  // A slider dragged over 70, 71, 72 is one step.
  for (const char* v : {"70", "71", "72"}) {
    expectOk(c.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", v}}));
  }
  EXPECT_EQ(blockOf(netState(c), "threshold")["properties"]["threshold"], "72");
  expectOk(c.request({{"op", "undo"}}));
  EXPECT_EQ(blockOf(netState(c), "threshold")["properties"]["threshold"], "128");  // the default again
  expectOk(c.request({{"op", "undo"}}));
  EXPECT_TRUE(netState(c)["links"].empty());
  expectOk(c.request({{"op", "redo"}}));
  expectOk(c.request({{"op", "redo"}}));
  json net = netState(c);
  EXPECT_EQ(net["links"].size(), 1u);
  EXPECT_EQ(blockOf(net, "threshold")["properties"]["threshold"], "72");
  EXPECT_FALSE(net["can_redo"]);
  expectContains(failure(c.request({{"op", "redo"}})), "nothing to redo");
  // A new edit clears the redo steps.
  expectOk(c.request({{"op", "undo"}}));
  expectOk(c.request({{"op", "rename_block"}, {"block", "gray"}, {"name", "mono"}}));
  net = netState(c);
  EXPECT_FALSE(net["can_redo"]);
  EXPECT_EQ(net["links"][0]["from"], "mono.image");
  EXPECT_EQ(net["links"][0]["type"], "sensor_msgs/Image");
}

TEST_F(DesignerTest, PropertyChangeReRunsOnlyThatBlockAndItsDownstream) {
  start();
  DesignerClient& c = connect();
  buildChain(c);
  addBlock(c, "imagenets/GaussianBlur", "blur");
  expectOk(c.request({{"op", "add_link"}, {"from", "gray.image"}, {"to", "blur.image"}}));
  json run = c.request({{"op", "run"}});
  expectOk(run);
  EXPECT_EQ(run["ran"].size(), 4u) << run.dump();
  EXPECT_TRUE(run["failed"].empty()) << run.dump();
  c.clear();

  const json reply = c.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", 90}});
  expectOk(reply);
  EXPECT_EQ(reply["run"]["ran"], json::array({"threshold"})) << reply.dump();
  EXPECT_EQ(reply["run"]["cached"], json::array({"source", "gray", "blur"})) << reply.dump();
  const json net = netState(c);
  EXPECT_EQ(blockOf(net, "source")["stats"]["runs"], 1);
  EXPECT_EQ(blockOf(net, "gray")["stats"]["runs"], 1);
  EXPECT_EQ(blockOf(net, "blur")["stats"]["runs"], 1);
  EXPECT_EQ(blockOf(net, "threshold")["stats"]["runs"], 2);
  // Each block's CPU time beside its wall time (the thread's own: within it, up to the clocks' grain).
  const json blurred = blockOf(net, "blur")["stats"];
  EXPECT_GT(blurred["last_cpu_ms"].get<double>(), 0.0) << blurred.dump();
  EXPECT_LE(blurred["last_cpu_ms"].get<double>(), blurred["last_ms"].get<double>() + 0.1) << blurred.dump();
  EXPECT_EQ(blurred["mean_cpu_ms"], blurred["last_cpu_ms"]) << blurred.dump();
  // The run's events came to the tab: threshold started and finished.
  c.waitForText([](const json& j) { return j.value("op", "") == "event" && j["kind"] == "finished" && j["block"] == "threshold"; },
                "threshold's finished event");

  // With auto_run off the change waits for `run`.
  expectOk(c.request({{"op", "auto_run"}, {"on", false}}));
  const json quiet = c.request({{"op", "set_property"}, {"block", "blur"}, {"property", "kernel_size"}, {"text", "7"}});
  expectOk(quiet);
  EXPECT_FALSE(quiet.contains("run"));
  run = c.request({{"op", "run"}});
  EXPECT_EQ(run["ran"], json::array({"blur"})) << run.dump();
  EXPECT_EQ(blockOf(netState(c), "source")["stats"]["runs"], 1);
}

TEST_F(DesignerTest, TwoTabsSeeEachOthersEdits) {
  start();
  DesignerClient& a = connect();
  DesignerClient& b = connect();
  expectOk(a.request({{"op", "hello"}}));
  expectOk(b.request({{"op", "hello"}}));
  addBlock(a, "imagenets/Grayscale", "gray");
  const json pushed = b.waitForText(
      [](const json& j) { return j.value("op", "") == "net" && j["blocks"].size() == 1 && j["blocks"][0]["name"] == "gray"; },
      "the net with a's block");
  EXPECT_TRUE(pushed["can_undo"]);
  expectOk(b.request({{"op", "remove_blocks"}, {"names", {"gray"}}}));
  a.waitForText([](const json& j) { return j.value("op", "") == "net" && j["blocks"].empty() && j["can_undo"] == true; },
                "the net without the block");
}

TEST_F(DesignerTest, SavedNetValidatesAndLoadsAsTheNetThatWasDrawn) {
  start();
  DesignerClient& c = connect();
  buildChain(c);
  expectOk(c.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", "77"}}));
  expectOk(c.request({{"op", "move_blocks"}, {"positions", {{"gray", {300, 40}}}}}));
  const std::string file = root() + "/drawn.yaml";
  const json saved = c.request({{"op", "save"}, {"path", file}});
  expectOk(saved);
  EXPECT_EQ(saved["file"], file);
  EXPECT_FALSE(netState(c)["dirty"]);

  const std::string cmd = std::string(IMAGENETS_TOOL) + " validate " + file + " > " + root() + "/validate.txt 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << readFile(root() + "/validate.txt");
  auto exec = Executor::loadFile(file);
  const Net& net = exec->net();
  ASSERT_EQ(net.nodes().size(), 3u);
  EXPECT_EQ(net.node(net.findNode("threshold")).block->info()->type, "imagenets/Threshold");
  EXPECT_EQ(std::get<int>(net.node(net.findNode("threshold")).block->propertyValue("threshold")), 77);
  const Endpoint in = net.node(net.findNode("threshold")).input_links[0];
  EXPECT_EQ(net.node(in.node).name, "gray");
  EXPECT_TRUE(exec->run().ok());
  expectContains(readFile(file), "designer:\n  positions: {gray: [300, 40]");
}

TEST_F(DesignerTest, SavingAnUnchangedHandWrittenNetChangesOnlyThePositions) {
  const std::string file = copyConfigNet("robust_marker_detection.yaml");
  const std::string original = readFile(file);
  start(file);
  DesignerClient& c = connect();
  EXPECT_EQ(netState(c)["yaml"], original);
  EXPECT_FALSE(netState(c)["dirty"]);
  expectOk(c.request({{"op", "move_blocks"}, {"positions", {{"gray", {120, 40}}, {"detector", {480.5, 60}}}}}));
  EXPECT_TRUE(netState(c)["dirty"]);
  expectOk(c.request({{"op", "save"}}));
  const std::string saved = readFile(file);
  EXPECT_EQ(saved, original + "designer:\n  positions: {detector: [480.5, 60], gray: [120, 40]}\n");
  EXPECT_EQ(setTopLevelSection(saved, "designer", ""), original);

  // Opened again, the positions come back; a second save writes the same bytes.
  expectOk(c.request({{"op", "open"}, {"path", file}}));
  EXPECT_EQ(blockOf(netState(c), "detector")["position"], json({480.5, 60}));
  expectOk(c.request({{"op", "save"}}));
  EXPECT_EQ(readFile(file), saved);

  // A real change rewrites the net; it still loads, with its doc kept.
  expectOk(c.request({{"op", "set_property"}, {"block", "detector"}, {"property", "min_confidence"}, {"text", "0.6"}}));
  expectOk(c.request({{"op", "save"}}));
  const std::string changed = readFile(file);
  expectContains(changed, "min_confidence: 0.6");
  expectContains(changed, "Robust 2D marker detection");
  expectContains(changed, "feedback: {property: threshold, from: 5, to: 250, step: 1, score: detector.confidence");
  expectContains(changed, "initial: otsu.threshold, good_enough: 0.9, coarse_step: 15, fine_radius: 7}");
  auto exec = Executor::loadFile(file);
  EXPECT_EQ(exec->net().nodes().size(), 6u);
}

TEST_F(DesignerTest, EveryConfigNetRoundTripsThroughTheDocument) {
  namespace fs = boost::filesystem;
  for (const auto& entry : fs::directory_iterator(fs::path(kSourceDir) / "config" / "nets")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    const std::string text = readFile(entry.path().string());
    const std::string dir = entry.path().parent_path().string();
    NetDocument doc = NetDocument::fromText(text, entry.path().string(), dir);
    EXPECT_EQ(doc.text(), text);  // unchanged: exactly the file
    doc.positions[doc.spec.blocks.front().name] = {1, 2};
    NetDocument again = NetDocument::fromText(doc.text(), entry.path().string(), dir);
    EXPECT_TRUE(again.sameNet(doc));
    EXPECT_EQ((again.positions.begin()->second), (std::array<double, 2>{1, 2}));
    // Written anew, the net parses to the same net.
    const std::string written = writeNetText(doc.spec, text);
    EXPECT_TRUE(NetDocument::fromText(written, entry.path().string(), dir).sameNet(doc)) << written;
  }
}

TEST_F(DesignerTest, WatchedPortsComeAsBinaryPreviewsAndRawPixels) {
  start();
  DesignerClient& c = connect();
  buildChain(c);
  expectOk(c.request({{"op", "run"}}));
  expectOk(c.request({{"op", "watch"}, {"ports", {"gray.image", "threshold.image"}}, {"mode", "preview"}}));
  DesignerClient::Message preview = c.waitForFrame("gray.image", "preview");
  EXPECT_EQ(preview.json["format"], "pixels");
  EXPECT_EQ(preview.json["channels"], 1);
  EXPECT_EQ(preview.json["type"], "sensor_msgs/Image");
  EXPECT_EQ(preview.json["width"], 1024);
  EXPECT_EQ(preview.json["preview_width"], 256);
  EXPECT_EQ(preview.json["preview_height"], 192);
  ASSERT_EQ(preview.payload.size(), 256u * 192u);
  // The thumbnail is the image made smaller, not another one.
  cv::Mat scene = cv::imread(kSourceDir + "/config/images/scene.png", cv::IMREAD_GRAYSCALE), small;
  cv::resize(scene, small, cv::Size(256, 192), 0, 0, cv::INTER_AREA);
  const cv::Mat thumb(192, 256, CV_8UC1, const_cast<char*>(preview.payload.data()));
  EXPECT_LT(cv::norm(thumb, small, cv::NORM_L1) / thumb.total(), 2.0);

  expectOk(c.request({{"op", "watch"}, {"ports", {"gray.image"}}, {"mode", "full"}}));
  DesignerClient::Message full = c.waitForFrame("gray.image", "full");
  EXPECT_EQ(full.json["format"], "raw");
  EXPECT_EQ(full.json["encoding"], "mono8");
  ASSERT_EQ(full.payload.size(), 1024u * 768u);
  // The pixel a page would show under the cursor is the executor's own pixel.
  cv::Mat gray = cv::imread(kSourceDir + "/config/images/scene.png", cv::IMREAD_GRAYSCALE);
  EXPECT_EQ(static_cast<unsigned char>(full.payload[300 * 1024 + 500]), gray.at<uchar>(300, 500));

  // A change of the threshold sends the new binary image, and nothing for the unchanged gray.
  c.clear();
  expectOk(c.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", "200"}}));
  DesignerClient::Message after = c.waitForFrame("threshold.image", "preview");
  EXPECT_GT(after.json["run"].get<long>(), preview.json["run"].get<long>());
  EXPECT_THROW(c.waitForFrame("gray.image", "preview", 0.5), std::runtime_error);
}

TEST_F(DesignerTest, FeedbackIsSetLikeTheNetFileAndItsTraceComesAsJson) {
  start();
  DesignerClient& c = connect();
  addBlock(c, "imagenets/ImageFileSource", "source");
  expectOk(c.request({{"op", "set_property"}, {"block", "source"}, {"property", "path"},
                      {"text", kSourceDir + "/config/images/marker_sample.png"}}));
  addBlock(c, "imagenets/CameraInfoFile", "camera");
  expectOk(c.request({{"op", "set_property"}, {"block", "camera"}, {"property", "path"},
                      {"text", imagenets::packageFile("imagenets_vision", "config/cameras/stereo_left.yaml")}}));
  addBlock(c, "imagenets/Grayscale", "gray");
  addBlock(c, "imagenets/Threshold", "threshold");
  addBlock(c, "imagenets/SquareMarkerDetector", "detector");
  expectOk(c.request({{"op", "set_property"}, {"block", "detector"}, {"property", "marker"},
                      {"text", imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml")}}));
  for (auto [from, to] : std::vector<std::pair<std::string, std::string>>{{"source.image", "gray.image"},
                                                                          {"gray.image", "threshold.image"},
                                                                          {"threshold.image", "detector.image"},
                                                                          {"gray.image", "detector.gray"},
                                                                          {"camera.camera_info", "detector.camera_info"}}) {
    expectOk(c.request({{"op", "add_link"}, {"from", from}, {"to", to}}));
  }
  expectContains(failure(c.request({{"op", "set_feedback"}, {"block", "threshold"},
                                    {"feedback", {{"property", "threshold"}, {"from", 40}, {"to", 80}, {"score", "detector.pose"}}}})),
                 "score port detector.pose is geometry_msgs/PoseStamped, not std_msgs/Float64");
  expectContains(failure(c.request({{"op", "set_feedback"}, {"block", "threshold"},
                                    {"feedback", {{"property", "threshold"}, {"form", 40}, {"score", "detector.confidence"}}}})),
                 "feedback: unknown key 'form'");
  expectOk(c.request({{"op", "set_feedback"}, {"block", "threshold"},
                      {"feedback", {{"property", "threshold"}, {"from", 40}, {"to", 80}, {"step", 5},
                                    {"score", "detector.confidence"}, {"goal", "maximize"}}}}));
  const json fb = blockOf(netState(c), "threshold")["feedback"];
  EXPECT_EQ(fb["from"], 40);
  EXPECT_EQ(fb["step"], 5);
  EXPECT_EQ(fb["score"], "detector.confidence");
  const json net = netState(c);
  bool has_trace_port = false;
  for (const auto& p : blockOf(net, "threshold")["outputs"]) has_trace_port |= p["name"] == "feedback_trace";
  EXPECT_TRUE(has_trace_port);

  expectOk(c.request({{"op", "run"}}));
  expectOk(c.request({{"op", "watch"}, {"ports", {"threshold.feedback_trace", "detector.confidence"}}}));
  const DesignerClient::Message trace = c.waitForFrame("threshold.feedback_trace", "preview");
  EXPECT_EQ(trace.json["format"], "json");
  const json value = json::parse(trace.payload);
  EXPECT_EQ(value["values"].size(), 9u) << value.dump();
  EXPECT_EQ(value["property"], "threshold");
  EXPECT_TRUE(value["chosen_value"].is_number());
  const json confidence = json::parse(c.waitForFrame("detector.confidence", "preview").payload);
  EXPECT_GT(confidence["data"].get<double>(), 0.5);

  // Renaming the score block renames it in the feedback too.
  expectOk(c.request({{"op", "rename_block"}, {"block", "detector"}, {"name", "det"}}));
  EXPECT_EQ(blockOf(netState(c), "threshold")["feedback"]["score"], "det.confidence");
}

TEST_F(DesignerTest, ExportsALaunchFileAndAGraph) {
  start();
  DesignerClient& c = connect();
  buildChain(c);
  const std::string launch = c.request({{"op", "export_launch"}})["text"];
  expectContains(launch, "<node pkg=\"nodelet\" type=\"nodelet\" name=\"gray\" args=\"load imagenets/Grayscale $(arg manager)\">");
  expectContains(launch, "<remap from=\"~in/image\" to=\"gray/out/image\"/>");
  expectContains(launch, "<param name=\"path\" type=\"str\" value=\"$(find imagenets_blocks)/config/images/scene.png\"/>");
  const std::string svg = c.request({{"op", "export_graph"}, {"expand", false}})["svg"];
  expectContains(svg, "<svg");
  expectContains(svg, "threshold");
}

TEST_F(DesignerTest, SubNetIsShownReadOnlyWithItsInnerBlocks) {
  const std::string file = copyConfigNet("segmentation_subnet.yaml");
  start();
  DesignerClient& c = connect();
  // An SubNet block needs its net to be built: it is added with its properties.
  expectOk(c.request({{"op", "add_block"}, {"type", "imagenets/SubNet"}, {"name", "seg"}, {"properties", {{"net", file}}}}));
  const json net = netState(c);
  EXPECT_TRUE(blockOf(net, "seg")["has_subnet"]);
  EXPECT_FALSE(blockOf(net, "seg")["inputs"].empty());
  const json sub = c.request({{"op", "subnet"}, {"block", "seg"}});
  expectOk(sub);
  EXPECT_TRUE(sub["net"]["readonly"]);
  EXPECT_FALSE(sub["net"]["blocks"].empty());
  EXPECT_EQ(sub["net"]["yaml"], readFile(file));
  expectContains(failure(c.request({{"op", "subnet"}, {"block", "nope"}})), "no block named 'nope'");
  expectOk(c.request({{"op", "subnet_open"}, {"block", "seg"}}));
  EXPECT_EQ(netState(c)["file"], file);
}

TEST_F(DesignerTest, YamlTextReplacesTheNetOrIsRefusedWithItsLine) {
  start();
  DesignerClient& c = connect();
  std::string e = failure(c.request({{"op", "set_yaml"},
                                     {"text", "blocks:\n  gray: {type: imagenets/Grayscale}\n  t: {type: imagenets/Thresold}\n"}}));
  expectContains(e, ":3: block 't': unknown block type 'imagenets/Thresold'");
  e = failure(c.request({{"op", "set_yaml"}, {"text", "blocks:\n  gray: {type: [\n"}}));
  expectContains(e, "malformed YAML");
  EXPECT_TRUE(netState(c)["blocks"].empty());
  const std::string text =
      "# my net\nblocks:\n  gray: {type: imagenets/Grayscale}  # gray\n  t: {type: imagenets/Threshold}\n"
      "links:\n  - gray.image -> t.image\ndesigner:\n  positions: {t: [5, 6]}\n";
  expectOk(c.request({{"op", "set_yaml"}, {"text", text}}));
  const json net = netState(c);
  EXPECT_EQ(net["yaml"], text);  // comments kept while the net is unchanged
  EXPECT_EQ(blockOf(net, "t")["position"], json({5, 6}));
  EXPECT_EQ(net["links"][0]["to"], "t.image");
}

TEST_F(DesignerTest, ATabThatFallsBehindGetsTheNewestValueNotEveryOne) {
  start();
  DesignerClient& editor = connect();
  DesignerClient& slow = connect();
  buildChain(editor);
  expectOk(editor.request({{"op", "run"}}));
  expectOk(slow.request({{"op", "watch"}, {"ports", {"threshold.image"}}, {"mode", "full"}}));
  const long first_run = slow.waitForFrame("threshold.image", "full").json["run"];
  slow.pauseReading();
  // 40 changes, each a new 786 kB binary image for the slow tab: far more than the socket buffers
  // hold while it does not read.
  const int changes = 40;
  for (int i = 0; i < changes; ++i) {
    const json reply = editor.request({{"op", "set_property"}, {"block", "threshold"}, {"property", "threshold"}, {"text", 100 + i}});
    ASSERT_EQ(reply["run"]["ran"], json::array({"threshold"}));
  }
  slow.resumeReading();
  int frames = 0;
  for (;;) {
    const DesignerClient::Message m = slow.waitForFrame("threshold.image", "full");
    ++frames;
    if (m.json["run"] == first_run + changes) break;  // the newest value, from the last run
  }
  EXPECT_LT(frames, changes);
}

TEST_F(DesignerTest, PasteMakesNamesUniqueAndKeepsItsLinksAndFeedback) {
  start();
  DesignerClient& c = connect();
  addBlock(c, "imagenets/Grayscale", "gray");
  const json pasted = c.request(
      {{"op", "paste"},
       {"blocks",
        {{{"name", "gray"}, {"type", "imagenets/Grayscale"}, {"position", {5, 5}}},
         {{"name", "threshold"}, {"type", "imagenets/Threshold"}, {"properties", {{"threshold", "99"}}}}}},
       {"links", {{{"from", "gray.image"}, {"to", "threshold.image"}}}}});
  expectOk(pasted);
  EXPECT_EQ(pasted["names"]["gray"], "gray_2");
  EXPECT_EQ(pasted["names"]["threshold"], "threshold");
  const json net = netState(c);
  EXPECT_EQ(net["blocks"].size(), 3u);
  ASSERT_EQ(net["links"].size(), 1u);
  EXPECT_EQ(net["links"][0]["from"], "gray_2.image");
  EXPECT_EQ(blockOf(net, "threshold")["properties"]["threshold"], "99");
  EXPECT_EQ(blockOf(net, "gray_2")["position"], json({5, 5}));
  // One undo step takes the whole paste away.
  expectOk(c.request({{"op", "undo"}}));
  EXPECT_EQ(netState(c)["blocks"].size(), 1u);
}
