// Net::build's named steps (NetBuilder), each run on its own: every step collects all of its
// errors with file:line, and a later step works on what the earlier ones built.
#include <gtest/gtest.h>

#include "imagenets/net_builder.h"
#include "test_blocks.h"

using namespace imagenets;

namespace {

std::string joined(const std::vector<std::string>& errors) {
  std::string out;
  for (const auto& e : errors) out += e + "\n";
  return out;
}

}  // namespace

TEST(NetBuilder, CreateBlocksCollectsEveryBlockAndPropertyError) {
  const NetSpec spec = parseNetText(R"(
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b: {type: test/Scael}
  c: {type: test/Scale, properties: {gain: lots, nope: 1}}
)", "steps.yaml", "");
  NetBuilder builder(spec);
  builder.createBlocks();
  const std::string errors = joined(builder.errors());
  EXPECT_EQ(builder.errors().size(), 3u) << errors;
  EXPECT_NE(errors.find("steps.yaml:4: block 'b': unknown block type 'test/Scael'; did you mean 'test/Scale'"),
            std::string::npos) << errors;
  EXPECT_NE(errors.find("steps.yaml:5: block 'c' (test/Scale): property 'gain': expected double, got 'lots'"),
            std::string::npos) << errors;
  EXPECT_NE(errors.find("steps.yaml:5: block 'c' (test/Scale): unknown property 'nope'"), std::string::npos) << errors;
  // The good block is built; the bad ones are left out.
  ASSERT_EQ(builder.net().nodes().size(), 1u);
  EXPECT_EQ(builder.net().nodes()[0].name, "a");
  EXPECT_THROW(builder.finish(), NetError);
}

TEST(NetBuilder, FeedbackGivesTheBlockATraceOutputWhenCreated) {
  NetBuilder builder(parseNetText(R"(
blocks:
  x: {type: test/Constant, feedback: {property: value, from: 0, to: 2, score: p.score}}
  p: {type: test/Parabola}
)", "fb.yaml", ""));
  builder.createBlocks();
  ASSERT_TRUE(builder.errors().empty()) << joined(builder.errors());
  EXPECT_GE(builder.net().nodes()[0].block->outputIndex("feedback_trace"), 0);
  EXPECT_LT(builder.net().nodes()[1].block->outputIndex("feedback_trace"), 0);
}

TEST(NetBuilder, LinkBlocksChecksNamesPortsAndTypesOfWhatWasCreated) {
  NetBuilder builder(parseNetText(R"(
blocks:
  a: {type: test/Constant}
  b: {type: test/Scale}
  gone: {type: test/Nothing}
links:
  - a.value -> b.in
  - a.value -> b.in
  - a.nope -> b.in
  - ghost.value -> b.in
  - gone.value -> b.in
)", "links.yaml", ""));
  builder.createBlocks();
  ASSERT_EQ(builder.errors().size(), 1u);  // gone: unknown type
  builder.linkBlocks();
  const std::string errors = joined(builder.errors());
  ASSERT_EQ(builder.errors().size(), 4u) << errors;
  EXPECT_NE(errors.find("links.yaml:8: link a.value -> b.in: input b.in is already linked from a.value"),
            std::string::npos) << errors;
  EXPECT_NE(errors.find("links.yaml:9: link a.nope -> b.in: block 'a' has no output port 'nope' (outputs: value "
                        "[std_msgs/Float64])"),
            std::string::npos) << errors;
  EXPECT_NE(errors.find("links.yaml:10: link ghost.value -> b.in: no block named 'ghost'"), std::string::npos) << errors;
  // A link to a block whose creation failed is not reported again.
  EXPECT_EQ(errors.find("link gone.value"), std::string::npos) << errors;
  EXPECT_TRUE(builder.net().nodes()[1].input_links[0].valid());
}

TEST(NetBuilder, OrderBlocksNamesTheBlocksOfACycle) {
  NetBuilder builder(parseNetText(R"(
blocks:
  a: {type: test/Add}
  b: {type: test/Scale}
  c: {type: test/Constant}
links: [a.sum -> b.in, b.out -> a.a, c.value -> a.b]
)", "cycle.yaml", ""));
  builder.createBlocks();
  builder.linkBlocks();
  ASSERT_TRUE(builder.errors().empty()) << joined(builder.errors());
  builder.orderBlocks();
  ASSERT_EQ(builder.errors().size(), 1u);
  EXPECT_EQ(builder.errors()[0],
            "cycle.yaml: the links form a cycle through blocks a, b (nets are acyclic; use feedback to tune a block "
            "from a downstream score)");
}

TEST(NetBuilder, CheckFeedbackRunsOnAWholeNetOnly) {
  NetBuilder builder(parseNetText(R"(
blocks:
  x: {type: test/Constant, feedback: {property: value, from: 0, to: 2, score: p.nope}}
  p: {type: test/Parabola}
links: [x.value -> p.x]
)", "check.yaml", ""));
  builder.createBlocks();
  builder.linkBlocks();
  builder.orderBlocks();
  builder.checkFeedback();
  ASSERT_EQ(builder.errors().size(), 1u);
  EXPECT_EQ(builder.errors()[0], "check.yaml:3: block 'x': feedback: score block 'p' has no output port 'nope'");
}
