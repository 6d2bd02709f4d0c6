// Runs through the protocol: cancel stops a long run at once and the net stays usable; save as
// into another folder keeps relative paths pointing at the same files; the exported launch file
// is one roslaunch reads; `imagenets designer` serves the net given on its command line.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "designer_test_util.h"
#include "imagenets/executor.h"
#include "imagenets/testing/read_file.h"

using namespace imagenets;
using namespace imagenets::designer;
using nlohmann::json;

namespace {

using imagenets::testing::readFile;

std::string commandOutput(const std::string& cmd, int& status) {
  std::string out;
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  status = pclose(pipe);
  return out;
}

}  // namespace

TEST_F(DesignerTest, CancelStopsALongRunAndTheNetStaysUsable) {
  const std::string file = copyConfigNet("robust_marker_detection.yaml");
  start(file);
  DesignerClient& c = connect();
  // 5101 sequential trials of the marker detector: far longer than a cancel takes to arrive.
  expectOk(c.request({{"op", "set_feedback"}, {"block", "threshold"},
                      {"feedback", {{"property", "threshold"}, {"from", 0}, {"to", 255}, {"step", 0.05},
                                    {"score", "detector.confidence"}, {"parallel", false}}}}));
  c.sendText(json{{"op", "run"}, {"id", "long run"}}.dump());
  c.waitForText([](const json& j) { return j.value("op", "") == "event" && j["kind"] == "trial"; }, "a feedback trial");
  expectOk(c.request({{"op", "cancel"}}));
  const json reply = c.waitForText([](const json& j) { return j.value("op", "") == "reply" && j["id"] == "long run"; },
                                   "the cancelled run's reply");
  EXPECT_TRUE(reply["ok"]);
  EXPECT_TRUE(reply["cancelled"]) << reply.dump();
  // The net is still there and runs.
  expectOk(c.request({{"op", "set_feedback"}, {"block", "threshold"},
                      {"feedback", {{"property", "threshold"}, {"from", 40}, {"to", 80}, {"step", 10},
                                    {"score", "detector.confidence"}}}}));
  const json again = c.request({{"op", "run"}});
  EXPECT_FALSE(again["cancelled"]);
  EXPECT_TRUE(again["failed"].empty()) << again.dump();
}

TEST_F(DesignerTest, SaveAsIntoAnotherFolderKeepsRelativePathsPointingAtTheSameFiles) {
  const std::string file = copyConfigNet("threshold_demo.yaml");
  start(file);
  DesignerClient& c = connect();
  const std::string target = root() + "/elsewhere/deeper/demo.yaml";
  boost::filesystem::create_directories(root() + "/elsewhere/deeper");
  expectOk(c.request({{"op", "save"}, {"path", target}}));
  expectContains(readFile(target), "path: ../../images/scene.png");
  auto exec = Executor::loadFile(target);
  EXPECT_TRUE(exec->run().ok());
  EXPECT_EQ(c.request({{"op", "hello"}})["net"]["file"], target);
}

TEST_F(DesignerTest, ExportedLaunchFileIsOneRoslaunchReads) {
  const std::string file = copyConfigNet("threshold_demo.yaml");
  start(file);
  DesignerClient& c = connect();
  const std::string launch = root() + "/threshold_demo.launch";
  std::ofstream(launch) << c.request({{"op", "export_launch"}})["text"].get<std::string>();
  int status = 0;
  const std::string nodes = commandOutput("roslaunch --nodes " + launch, status);
  EXPECT_EQ(status, 0) << nodes;
  for (const char* node : {"/threshold_demo/imagenets_manager", "/threshold_demo/source", "/threshold_demo/gray",
                           "/threshold_demo/blur", "/threshold_demo/threshold"}) {
    expectContains(nodes, node);
  }
  const std::string params = commandOutput("roslaunch --dump-params " + launch, status);
  EXPECT_EQ(status, 0) << params;
  expectContains(params, "/threshold_demo/threshold/threshold: 60");
  expectContains(params, "/threshold_demo/blur/kernel_size: 3");
  expectContains(params, "/threshold_demo/source/path: " + root() + "/images/scene.png");
}

TEST_F(DesignerTest, ToolServesTheNetGivenOnItsCommandLine) {
  int status = 0;
  const std::string usage = commandOutput(std::string(IMAGENETS_TOOL) + " designer --port many", status);
  EXPECT_EQ(WEXITSTATUS(status), 2);
  expectContains(usage, "--port 'many' is not an integer");
  expectContains(commandOutput(std::string(IMAGENETS_TOOL) + " designer --colour", status), "unknown option '--colour'");
  EXPECT_EQ(WEXITSTATUS(status), 2);

  const std::string file = copyConfigNet("threshold_demo.yaml");
  int out[2];
  ASSERT_EQ(pipe(out), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out[1], 1);
    close(out[0]);
    execl(IMAGENETS_TOOL, IMAGENETS_TOOL, "designer", file.c_str(), "--port", "0", "--root", root().c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  close(out[1]);
  FILE* stream = fdopen(out[0], "r");
  char line[512] = {0};
  ASSERT_NE(fgets(line, sizeof line, stream), nullptr);  // "ImageNet Designer: http://127.0.0.1:PORT/ ..."
  const std::string first(line);
  const auto colon = first.find(":", first.find("127.0.0.1"));
  ASSERT_NE(colon, std::string::npos) << first;
  const int port = std::stoi(first.substr(colon + 1));
  {
    DesignerClient client(port);
    const json net = client.request({{"op", "hello"}})["net"];
    EXPECT_EQ(net["file"], file);
    EXPECT_EQ(net["blocks"].size(), 4u);
  }
  kill(pid, SIGTERM);
  int exit_status = 0;
  waitpid(pid, &exit_status, 0);
  fclose(stream);
  EXPECT_TRUE(WIFEXITED(exit_status));
  EXPECT_EQ(WEXITSTATUS(exit_status), 0);
}

TEST_F(DesignerTest, ANetFileThatDoesNotExistYetIsANewNetSavedUnderThatName) {
  const std::string file = root() + "/new_net.yaml";
  start(file);
  DesignerClient& c = connect();
  EXPECT_EQ(c.request({{"op", "hello"}})["net"]["file"], file);
  expectOk(c.request({{"op", "add_block"}, {"type", "imagenets/Grayscale"}, {"name", "gray"}}));
  expectOk(c.request({{"op", "save"}}));
  expectContains(readFile(file), "gray:");
}

TEST_F(DesignerTest, ANetThatDoesNotLoadLeavesAnEmptyNetAndItsErrors) {
  const std::string file = root() + "/broken.yaml";
  std::ofstream(file) << "blocks:\n  a: {type: imagenets/Nothing}\n";
  DesignerServer::Options options;
  options.port = 0;
  DesignerServer server(options);
  EXPECT_FALSE(server.session().openStartupNet(file));
  const json net = server.session().netState();
  EXPECT_TRUE(net["blocks"].empty());
  ASSERT_EQ(net["errors"].size(), 1u);
  expectContains(net["errors"][0], file + ":2: block 'a': unknown block type 'imagenets/Nothing'");
}
