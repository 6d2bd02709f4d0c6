// The Designer's share of the time from a property change to the updated preview: a C++
// WebSocket client changes Threshold's property on a 1024x768 image chain (source -> gray ->
// blur -> threshold) and waits for threshold.image's new preview frame; the same change on a
// plain in-process Executor gives the engine's own time. Median / p95 over 50 changes each.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include <boost/filesystem.hpp>

#include "designer_client.h"
#include "imagenets/bench_summary.h"
#include "designer_server.h"
#include "imagenets/executor.h"

using namespace imagenets;
using namespace imagenets::designer;
using Clock = std::chrono::steady_clock;

namespace {

const int kChanges = 50;

std::string chain() {
  return std::string("blocks:\n") + "  source: {type: imagenets/ImageFileSource, properties: {path: " IMAGENETS_SOURCE_DIR
                                    "/config/images/scene.png}}\n" +
         "  gray: {type: imagenets/Grayscale}\n  blur: {type: imagenets/GaussianBlur, properties: {kernel_size: 5}}\n" +
         "  threshold: {type: imagenets/Threshold, properties: {threshold: 60}}\n" +
         "links:\n  - source.image -> gray.image\n  - gray.image -> blur.image\n  - blur.image -> threshold.image\n";
}

void print(const char* what, std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  const double median = ms[ms.size() / 2];
  const double p95 = ms[std::min(ms.size() - 1, static_cast<size_t>(0.95 * static_cast<double>(ms.size())))];
  std::printf("%-66s median %7.2f ms   p95 %7.2f ms\n", what, median, p95);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  const auto root = boost::filesystem::temp_directory_path() / boost::filesystem::unique_path("bench-designer-%%%%");
  boost::filesystem::create_directories(root);

  // The engine alone: setProperty + run() re-runs threshold only.
  std::vector<double> engine;
  {
    Executor exec(Net::build(parseNetText(chain(), "chain.yaml", root.string())));
    exec.run();
    for (int i = 0; i < kChanges; ++i) {
      const auto t0 = Clock::now();
      exec.setPropertyText("threshold", "threshold", std::to_string(61 + i));
      const RunReport report = exec.run();
      engine.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
      if (report.ran.size() != 1) std::fprintf(stderr, "unexpected: %zu blocks ran\n", report.ran.size());
    }
  }

  // The Designer: request sent -> new preview frame received by the client.
  std::vector<double> designer;
  {
    DesignerServer::Options options;
    options.port = 0;
    options.session.roots = {root.string()};
    DesignerServer server(options);
    server.start();
    DesignerClient client(server.port());
    client.request({{"op", "hello"}});
    client.request({{"op", "set_yaml"}, {"text", chain()}});
    client.request({{"op", "run"}});
    client.request({{"op", "watch"}, {"ports", {"threshold.image"}}, {"mode", "preview"}});
    long last_run = client.waitForFrame("threshold.image", "preview").json["run"];
    for (int i = 0; i < kChanges; ++i) {
      client.clear();
      const auto t0 = Clock::now();
      client.sendText(nlohmann::json{{"op", "set_property"}, {"id", 1000 + i}, {"block", "threshold"},
                                     {"property", "threshold"}, {"text", std::to_string(61 + i)}}
                          .dump());
      DesignerClient::Message frame = client.waitFor(
          [&](const DesignerClient::Message& m) {
            return m.binary && m.json.value("port", "") == "threshold.image" && m.json.value("run", 0L) > last_run;
          },
          "the new preview");
      designer.push_back(std::chrono::duration<double, std::milli>(frame.received - t0).count());
      last_run = frame.json["run"];
    }
  }
  boost::filesystem::remove_all(root);

  std::printf("1024x768 chain source -> gray -> blur -> threshold, %d changes of threshold.threshold\n", kChanges);
  print("executor: setPropertyText + run() in process", engine);
  print("designer: set_property sent -> threshold.image preview frame received", designer);
  std::printf("designer server overhead at the median: %.2f ms (the page's share: bench/designer_preview.mjs)\n",
              median(designer) - median(engine));
  imagenets::printSummaryRow("Designer server: set_property -> preview frame at a C++ client, ms, vs executor alone",
                             median(designer), median(engine), "", false);
  return 0;
}
