// Every load error names its culprit (file:line, block, port, property, value), and a failed load
// leaves nothing behind.
#include <fstream>

#include <gtest/gtest.h>

#include "imagenets/executor.h"
#include "imagenets/net.h"

using namespace imagenets;

namespace {

// Builds the net from `yaml` and returns the error text ("" if it loaded).
std::string loadError(const std::string& yaml) {
  try {
    Executor executor(Net::build(parseNetText(yaml, "test.yaml", "")), ExecutorOptions{1});
  } catch (const NetError& e) {
    return e.what();
  }
  return "";
}

void expectContains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "missing \"" << part << "\" in:\n" << text;
}

const char* kGood = R"(
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b: {type: test/Scale, properties: {gain: 3}}
links:
  - a.value -> b.in
)";

}  // namespace

TEST(NetLoading, AcceptsAGoodNet) { EXPECT_EQ(loadError(kGood), ""); }

TEST(NetLoading, UnknownBlockTypeSuggestsNearestNames) {
  std::string e = loadError("blocks:\n  a: {type: test/Constnt}\n");
  expectContains(e, "test.yaml:2");
  expectContains(e, "block 'a': unknown block type 'test/Constnt'");
  expectContains(e, "did you mean 'test/Constant'");
}

TEST(NetLoading, UnknownPortListsTheBlocksPorts) {
  std::string e = loadError(R"(
blocks:
  a: {type: test/Constant}
  b: {type: test/Scale}
links:
  - a.valu -> b.in
)");
  expectContains(e, "test.yaml:6");
  expectContains(e, "block 'a' has no output port 'valu' (outputs: value [std_msgs/Float64])");
}

TEST(NetLoading, LinkBetweenDifferentTypesIsRejected) {
  std::string e = loadError(R"(
blocks:
  a: {type: test/Constant}
  b: {type: test/Barrier}
  c: {type: test/Scale}
links:
  - a.value -> b.in
  - b.value -> c.in
)");
  EXPECT_EQ(e, "");  // same types: fine
  // FeedbackTrace into a Float64 input: different types.
  e = loadError(R"(
blocks:
  a: {type: test/Constant, feedback: {property: value, from: 0, to: 2, score: p.score}}
  p: {type: test/Parabola}
  c: {type: test/Scale}
links:
  - a.value -> p.x
  - a.feedback_trace -> c.in
)");
  expectContains(e, "link a.feedback_trace -> c.in: type mismatch: output is imagenets/FeedbackTrace, input is std_msgs/Float64");
}

TEST(NetLoading, InputLinkedTwiceIsRejected) {
  std::string e = loadError(R"(
blocks:
  a: {type: test/Constant}
  b: {type: test/Constant}
  c: {type: test/Scale}
links:
  - a.value -> c.in
  - b.value -> c.in
)");
  expectContains(e, "test.yaml:8");
  expectContains(e, "input c.in is already linked from a.value");
}

TEST(NetLoading, CycleIsRejectedNamingItsBlocks) {
  std::string e = loadError(R"(
blocks:
  a: {type: test/Add}
  b: {type: test/Scale}
links:
  - a.sum -> b.in
  - b.out -> a.a
)");
  expectContains(e, "cycle through blocks a, b");
}

TEST(NetLoading, UnknownPropertyListsKnownOnes) {
  std::string e = loadError("blocks:\n  s: {type: test/Scale, properties: {gian: 2}}\n");
  expectContains(e, "test.yaml:2");
  expectContains(e, "block 's' (test/Scale): unknown property 'gian' (known: gain, offset, fail)");
}

TEST(NetLoading, WrongPropertyTypeNamesValue) {
  std::string e = loadError("blocks:\n  s: {type: test/Scale, properties: {offset: many}}\n");
  expectContains(e, "block 's' (test/Scale): property 'offset': expected int, got 'many'");
}

TEST(NetLoading, OutOfRangePropertyNamesRange) {
  std::string e = loadError("blocks:\n  s: {type: test/Scale, properties: {offset: 5000}}\n");
  expectContains(e, "property 'offset': value 5000 is out of range [-1000, 1000]");
}

TEST(NetLoading, MalformedYamlGivesLineAndColumn) {
  std::string e = loadError("blocks:\n  a: {type: test/Constant\n  b: [\n");
  expectContains(e, "test.yaml:");
  expectContains(e, "malformed YAML");
}

TEST(NetLoading, UnreadableFileIsNamed) {
  try {
    Net::loadFile("/nonexistent/net.yaml");
    FAIL();
  } catch (const NetError& e) {
    expectContains(e.what(), "/nonexistent/net.yaml: cannot read net file");
  }
}

TEST(NetLoading, ReportsEveryErrorAtOnce) {
  std::string e = loadError(R"(
blocks:
  a: {type: test/Nope}
  s: {type: test/Scale, properties: {gain: x}}
)");
  expectContains(e, "unknown block type 'test/Nope'");
  expectContains(e, "property 'gain'");
}

TEST(NetLoading, LoadsFromAFileAndResolvesRelativeNames) {
  const std::string path = ::testing::TempDir() + "/good_net.yaml";
  std::ofstream(path) << kGood;
  auto net = Net::loadFile(path);
  EXPECT_EQ(net->nodes().size(), 2u);
  EXPECT_EQ(net->origin(), path);
  EXPECT_EQ(resolvePath("img.png", "/data/nets"), "/data/nets/img.png");
  EXPECT_EQ(resolvePath("/abs/img.png", "/data/nets"), "/abs/img.png");
}
