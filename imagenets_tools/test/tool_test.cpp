// The `imagenets` command line tool, run as a user runs it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "imagenets/testing/command_runner.h"
#include "imagenets/testing/read_file.h"

namespace {

using imagenets::testing::expectContains;
using imagenets::testing::readFile;
using imagenets::testing::tempPath;
using imagenets::testing::tool;  // `imagenets ARGS`, run in imagenets_blocks' folder
using Result = imagenets::testing::CommandResult;

}  // namespace

TEST(Tool, BlocksListsByCategoryWithPortsAndProperties) {
  Result r = tool("blocks");
  EXPECT_EQ(r.status, 0);
  expectContains(r.output, "[segmentation]");
  expectContains(r.output, "imagenets/Threshold - Fixed threshold");
  expectContains(r.output, "property threshold (int) = 128 [0, 255]");
  expectContains(r.output, "in  image [sensor_msgs/Image]");
  // Alphabetical within a category.
  EXPECT_LT(r.output.find("imagenets/GaussianBlur"), r.output.find("imagenets/Grayscale"));
}

TEST(Tool, BlocksFiltersByCategoryAndType) {
  Result r = tool("blocks --category preprocessing");
  EXPECT_EQ(r.status, 0);
  expectContains(r.output, "imagenets/Grayscale");
  EXPECT_EQ(r.output.find("imagenets/Threshold"), std::string::npos);
  r = tool("blocks --output-type std_msgs/Float64");
  expectContains(r.output, "imagenets/SegmentationQuality");
  EXPECT_EQ(r.output.find("imagenets/Grayscale "), std::string::npos);
  EXPECT_EQ(tool("blocks --category nothing-here").status, 1);
}

TEST(Tool, ValidateSaysOkOrListsErrors) {
  Result ok = tool("validate config/nets/threshold_demo.yaml");
  EXPECT_EQ(ok.status, 0);
  expectContains(ok.output, "OK config/nets/threshold_demo.yaml");
  const std::string bad = tempPath("bad.yaml");
  std::ofstream(bad) << "blocks:\n  t: {type: imagenets/Treshold}\n  g: {type: imagenets/Grayscale, properties: {x: 1}}\n";
  Result r = tool("validate " + bad);
  EXPECT_EQ(r.status, 1);
  expectContains(r.output, bad + ":2: block 't': unknown block type 'imagenets/Treshold'; did you mean 'imagenets/Threshold'");
  expectContains(r.output, bad + ":3: block 'g' (imagenets/Grayscale): unknown property 'x'");
}

// Every net shipped in imagenets_blocks' config/nets loads (block types, properties, links,
// sub-nets, feedback).
TEST(Tool, ValidateAcceptsEveryShippedNet) {
  std::vector<std::string> nets;
  for (const auto& e : boost::filesystem::directory_iterator("config/nets")) {
    if (e.path().extension() == ".yaml") nets.push_back("config/nets/" + e.path().filename().string());
  }
  for (const char* must : {"config/nets/robust_marker_detection.yaml", "config/nets/calibration_marker_detection.yaml"}) {
    EXPECT_NE(std::find(nets.begin(), nets.end(), must), nets.end()) << must;
  }
  for (const auto& net : nets) {
    Result r = tool("validate " + net);
    EXPECT_EQ(r.status, 0) << r.output;
    expectContains(r.output, "OK " + net);
  }
}

TEST(Tool, RunWritesOutputsAndTimings) {
  const std::string dir = tempPath("run_out");
  Result r = tool("run config/nets/threshold_demo.yaml --set threshold.threshold=90 --output-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "4 blocks ran, 0 failed");
  expectContains(r.output, "threshold               ok             1");
  expectContains(r.output, "last ms     mean ms last CPU ms mean CPU ms");
  // Progress lines from the run events, one per block as it finishes.
  expectContains(r.output, "[4/4] ");
  expectContains(r.output, "] threshold: ok (");
  expectContains(r.output, " ms, CPU ");
  EXPECT_TRUE(boost::filesystem::exists(dir + "/threshold.image.png"));
  EXPECT_TRUE(boost::filesystem::exists(dir + "/gray.image.png"));
  // A bad --set is named and nothing runs.
  r = tool("run config/nets/threshold_demo.yaml --set threshold.threshold=900");
  EXPECT_EQ(r.status, 1);
  expectContains(r.output, "config/nets/threshold_demo.yaml:15: block 'threshold' (imagenets/Threshold): property "
                           "'threshold': value 900 is out of range [0, 255]");
  r = tool("run config/nets/threshold_demo.yaml --set treshold.threshold=90");
  EXPECT_EQ(r.status, 2);  // a usage error
  expectContains(r.output, "config/nets/threshold_demo.yaml has no block 'treshold'");
}

TEST(Tool, RunSetAllOfAPropertyNoBlockHasIsAUsageError) {
  Result r = tool("run config/nets/threshold_demo.yaml --set-all no_such_property=1");
  EXPECT_EQ(r.status, 2);  // a usage error
  expectContains(r.output, "no block of config/nets/threshold_demo.yaml or its sub-nets has a property 'no_such_property'");
}

TEST(Tool, RunWritesTheFeedbackTrace) {
  const std::string dir = tempPath("fb_out");
  Result r = tool("run config/nets/feedback_threshold.yaml --trials --output-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "threshold: feedback trial 41 of 41: threshold = ");
  const std::string trace = readFile(dir + "/threshold.feedback_trace.yaml");
  expectContains(trace, "trials: 41");
  expectContains(trace, "stop_reason: all_tried");
  expectContains(trace, "found: 1");
  EXPECT_TRUE(boost::filesystem::exists(dir + "/threshold.feedback_trace.png"));
}

TEST(Tool, DetectByDefaultFindsTheMarkerInADimSceneThatThePapersRangeMisses) {
  // Illumination 18 %, dark wall: the paper is darker than 40, so every threshold of the
  // paper's 40..80 merges the black border with the margin and the wall (docs/markers.md).
  const std::string dir = tempPath("dim_scene");
  Result r = tool("run config/nets/marker_image_generation.yaml --quiet --set render.illumination=0.18 "
                  "--set render.background=0.1 --set render.tilt=0 --set render.supersampling=2 --output-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string image = dir + "/render.image.png";
  const std::string common = "detect --marker $(rospack find imagenets_vision)/config/markers/gripper.yaml --camera $(rospack find imagenets_vision)/config/cameras/stereo_left.yaml ";
  r = tool(common + "--feedback 40:80:1 " + image, true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "found: false");
  r = tool(common + image, true);  // no options: the net's own feedback (Otsu first, 5..250)
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "found: true");
  const size_t at = r.output.find("threshold: ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_LT(std::stoi(r.output.substr(at + 11)), 40) << r.output;
  expectContains(r.output, "translation: [");
  // --coarse-to-fine orders a --feedback range; alone it would silently do nothing.
  r = tool(common + "--coarse-to-fine " + image);
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "--coarse-to-fine orders a --feedback FROM:TO:STEP range");
}

TEST(Tool, DetectATargetFilePrintsItsCornersWithIdsAndThePose) {
  const std::string dir = tempPath("target_scene");
  const std::string targets = "$(rospack find imagenets_vision)/config/targets/";
  Result r = tool("run config/nets/marker_image_generation.yaml --quiet --set render.target=" + targets +
                  "aprilgrid_36h11_4x3.yaml --set render.distance=0.45 --set render.tilt=20 --set render.supersampling=2 "
                  "--output-dir " + dir);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string image = dir + "/render.image.png";
  const std::string camera = " --camera $(rospack find imagenets_vision)/config/cameras/stereo_left.yaml ";
  r = tool("detect --target " + targets + "aprilgrid_36h11_4x3.yaml" + camera + image, true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "  type: apriltag\n  found: true\n");
  expectContains(r.output, "  tags: 12\n");
  expectContains(r.output, "  ids: [0, 1, 2, 3, 4, 5, 6, 7, ");
  expectContains(r.output, "translation: [");
  // The true pose: 0.45 m in front of the camera.
  const size_t at = r.output.find("translation: [");
  ASSERT_NE(at, std::string::npos);
  std::stringstream t(r.output.substr(at + 14));
  double x, y, z;
  char comma;
  t >> x >> comma >> y >> comma >> z;
  EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 0.45, 0.001) << r.output;

  // A square marker's target file works as --marker did.
  r = tool("detect --target " + targets + "gripper_square_marker.yaml" + camera + image, true);
  EXPECT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "found: false");

  // A bad target file: its name and key, before any image.
  const std::string bad = tempPath("bad_target.yaml");
  std::ofstream(bad) << "type: apriltag\nfamily: tag36h11\nid: 600\nsize: 0.06\n";
  r = tool("detect --target " + bad + camera + image);
  EXPECT_EQ(r.status, 1) << r.output;
  expectContains(r.output, bad + ": 'id': 600 out of range: family tag36h11 has ids 0..586");
  r = tool("detect --target " + targets + "apriltag_36h11_60mm.yaml --threshold 40" + camera + image);
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "--threshold / --feedback belong to a square marker");
}

TEST(Tool, MarkerStudyWithDecoysCountsFalsePositives) {
  // Three views (tilt 0, 35 and 70 deg at pan 15) of the paper's even lighting, each also with a decoy in
  // the marker's place; the calibration's net given by --calibration-net.
  const std::string dir = tempPath("decoys");
  const Result r = tool("marker-study --conditions even --quick --pan 15:15:90 --decoys --threads 2 "
                        "--calibration-net config/nets/calibration_marker_detection.yaml -o " + dir, true);
  ASSERT_EQ(r.status, 0) << r.output;
  expectContains(r.output, "false positives on decoys: ours / apriltag |");
  expectContains(r.output, "| even | detect | 100.0 % / 100.0 % |");
  expectContains(r.output, "| even | calibration | 100.0 % / 100.0 % |");
  expectContains(r.output, "| 0/3 / 0/3 |");  // no decoy taken for the marker
  std::ifstream csv(dir + "/study.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.substr(header.size() - 6), ",decoy") << header;
  const Result bad = tool("marker-study --quick --calibration-net config/nets/no_such_net.yaml -o " + dir);
  EXPECT_NE(bad.status, 0);
  expectContains(bad.output, "no_such_net.yaml");
}

TEST(Tool, GraphDrawsAnSvg) {
  const std::string svg = tempPath("net.svg");
  Result r = tool("graph config/nets/feedback_threshold.yaml -o " + svg);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string drawing = readFile(svg);
  expectContains(drawing, "<svg");
  expectContains(drawing, "threshold");
  expectContains(drawing, "feedback: threshold (max)");
}

// The sub-command names from `imagenets --help`: one line each, "  NAME  summary".
std::vector<std::string> subCommands(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help.substr(help.find("commands:\n") + 10));
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string name, summary;
    words >> name;
    std::getline(words, summary);
    EXPECT_EQ(line.rfind("  ", 0), 0u) << "not a sub-command line: '" << line << "'";
    EXPECT_GT(summary.size(), 10u) << "sub-command '" << name << "' has no one-line summary";
    names.push_back(name);
  }
  return names;
}

TEST(Tool, HelpListsEverySubCommandOnOneLine) {
  for (const std::string flag : {"--help", "-h"}) {
    Result r = tool(flag, true);
    EXPECT_EQ(r.status, 0) << flag;
    expectContains(r.output, "usage: imagenets COMMAND");
    const auto names = subCommands(r.output);
    for (const char* known : {"blocks", "validate", "run", "graph", "detect", "print-marker", "marker-study"}) {
      EXPECT_NE(std::find(names.begin(), names.end(), known), names.end()) << known << " missing in:\n" << r.output;
    }
  }
}

TEST(Tool, EverySubCommandAnswersHelpWithItsUsage) {
  const auto names = subCommands(tool("--help", true).output);
  ASSERT_FALSE(names.empty());
  for (const auto& name : names) {
    for (const std::string flag : {"--help", "-h"}) {
      // Help wins over other arguments, even ones that would be errors or would start work.
      Result r = tool(name + " " + flag + " --no-such-option", true);
      EXPECT_EQ(r.status, 0) << name << " " << flag << ":\n" << r.output;
      EXPECT_EQ(r.output.rfind("usage: imagenets " + name, 0), 0u) << name << " " << flag << ":\n" << r.output;
    }
  }
}

TEST(Tool, AWrongOptionIsNamedWithTheUsage) {
  for (const auto& name : subCommands(tool("--help", true).output)) {
    Result r = tool(name + " --no-such-option");
    EXPECT_EQ(r.status, 2) << name << ":\n" << r.output;
    expectContains(r.output, "imagenets " + name + ": unknown option '--no-such-option'");
    expectContains(r.output, "usage: imagenets " + name);
  }
  Result r = tool("run config/nets/threshold_demo.yaml --threads many");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "imagenets run: --threads 'many' is not an integer");
}

TEST(Tool, HelpListsTheFlagsWithTheirDefaults) {
  Result r = tool("run --help", true);
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* flag : {"--set arg", "--set-all arg", "-o [ --output-dir ] arg", "--threads arg (=0)", "-q [ --quiet ]",
                           "--trials", "NET"}) {
    expectContains(r.output, flag);
  }
  r = tool("detect -h", true);
  for (const char* flag : {"--marker arg", "--target arg", "--camera arg", "--threshold arg", "--feedback arg",
                           "--coarse-to-fine", "--net arg", "IMAGE"}) {
    expectContains(r.output, flag);
  }
}

TEST(Tool, FlagErrorsNameTheFlagOrArgument) {
  Result r = tool("run config/nets/threshold_demo.yaml --thread 2");  // no guessing of abbreviations
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "imagenets run: unknown option '--thread'");
  r = tool("validate config/nets/threshold_demo.yaml other.yaml");
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "imagenets validate: unexpected argument 'other.yaml'");
  r = tool("run config/nets/threshold_demo.yaml --output-dir");
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "imagenets run: --output-dir needs a value");
  r = tool("print-marker --marker m.yaml -o m.png --dpi high");
  EXPECT_EQ(r.status, 2) << r.output;
  expectContains(r.output, "imagenets print-marker: --dpi 'high' is not a number");
}

TEST(Tool, UnknownCommandAndMissingArgumentsAreUsageErrors) {
  EXPECT_EQ(tool("frobnicate").status, 2);
  Result r = tool("graph config/nets/threshold_demo.yaml");
  EXPECT_EQ(r.status, 2);
  expectContains(r.output, "usage: imagenets graph");
}
