// Nets written back as text: what parseNetText reads from the written text is the same net, docs
// are kept, top-level sections are replaced without touching other lines, and the loader ignores
// the `designer:` section an editor keeps beside the net.
#include <gtest/gtest.h>

#include "imagenets/executor.h"
#include "imagenets/graph.h"
#include "imagenets/net_writer.h"

using namespace imagenets;

namespace {

const char* kNet = R"(# a comment the writer cannot keep
doc: >
  Two numbers, scaled and added.
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b:
    type: test/Scale
    doc: the gain is tuned
    properties: {gain: 3, offset: -4}
    feedback: {property: gain, from: 0.5, to: 2.5, step: 0.1, score: score.score, goal: minimize, search: coarse_to_fine, parallel: false,
               initial: [a.value, 1.25], good_enough: -0.5, coarse_step: 0.5, fine_radius: 0.2}
  c: {type: test/Barrier, properties: {group: "a: b, c", parties: 1}}
  score: {type: test/Parabola, properties: {peak: 4}}
links:
  - a.value -> b.in
  - b.out -> score.x
)";

std::string rewrite(const std::string& text) { return writeNetText(parseNetText(text, "t.yaml", ""), text); }

}  // namespace

TEST(NetWriter, WrittenNetReadsBackAsTheSameNet) {
  const NetSpec spec = parseNetText(kNet, "t.yaml", "");
  const std::string text = writeNetText(spec, kNet);
  const NetSpec back = parseNetText(text, "t.yaml", "");
  ASSERT_EQ(back.blocks.size(), spec.blocks.size()) << text;
  for (size_t i = 0; i < spec.blocks.size(); ++i) {
    EXPECT_EQ(back.blocks[i].name, spec.blocks[i].name);
    EXPECT_EQ(back.blocks[i].type, spec.blocks[i].type);
    ASSERT_EQ(back.blocks[i].properties.size(), spec.blocks[i].properties.size()) << text;
    for (size_t p = 0; p < spec.blocks[i].properties.size(); ++p) {
      EXPECT_EQ(back.blocks[i].properties[p].name, spec.blocks[i].properties[p].name);
      EXPECT_EQ(back.blocks[i].properties[p].text, spec.blocks[i].properties[p].text) << text;
    }
  }
  const FeedbackSpec& f = *back.blocks[1].feedback;
  const FeedbackSpec& g = *spec.blocks[1].feedback;
  EXPECT_EQ(f.property, "gain");
  EXPECT_EQ(f.values, g.values) << text;
  EXPECT_EQ(f.score_block, "score");
  EXPECT_FALSE(f.maximize);
  EXPECT_EQ(f.search, "coarse_to_fine");
  EXPECT_FALSE(f.parallel);
  ASSERT_EQ(f.initial.size(), 2u) << text;
  EXPECT_EQ(f.initial[0].str(), "a.value");
  EXPECT_EQ(f.initial[1].value, 1.25);
  EXPECT_EQ(f.good_enough, -0.5);
  EXPECT_EQ(f.coarse_step, 0.5);
  EXPECT_EQ(f.fine_radius, 0.2);
  ASSERT_EQ(back.links.size(), 2u);
  EXPECT_EQ(back.links[1].from_block + "." + back.links[1].from_port + " -> " + back.links[1].to_block + "." +
                back.links[1].to_port,
            "b.out -> score.x");
  // Writing is stable, and the written net builds.
  EXPECT_EQ(writeNetText(back, text), text);
  EXPECT_NO_THROW(Executor(Net::build(back), ExecutorOptions{1}));
}

TEST(NetWriter, KeepsTheNetsAndTheBlocksDocs) {
  const std::string text = rewrite(kNet);
  EXPECT_NE(text.find("Two numbers, scaled and added."), std::string::npos) << text;
  EXPECT_NE(text.find("doc: the gain is tuned"), std::string::npos) << text;
}

TEST(NetWriter, ABlockAddedSinceThePreviousTextIsWritten) {
  // An editor adds a block the previous text does not have (here after removing all it had).
  NetSpec spec = parseNetText(kNet, "t.yaml", "");
  spec.links.clear();
  spec.blocks.clear();
  BlockSpec added;
  added.name = "image_file_source";
  added.type = "test/Constant";
  spec.blocks.push_back(added);
  std::string text;
  ASSERT_NO_THROW(text = writeNetText(spec, kNet));
  EXPECT_NE(text.find("image_file_source:\n    type: test/Constant"), std::string::npos) << text;
  EXPECT_NE(text.find("Two numbers, scaled and added."), std::string::npos) << text;
  EXPECT_EQ(parseNetText(text, "t.yaml", "").blocks.size(), 1u);
}

TEST(NetWriter, FeedbackCandidatesThatAreNotEvenlySpacedAreWrittenAsValues) {
  const std::string net = "blocks:\n  a: {type: test/Constant, feedback: {property: value, values: [1, 2, 5], score: a.value}}\n";
  const std::string text = rewrite(net);
  EXPECT_NE(text.find("values: [1, 2, 5]"), std::string::npos) << text;
  EXPECT_EQ(parseNetText(text, "t.yaml", "").blocks[0].feedback->values, (std::vector<double>{1, 2, 5}));
}

TEST(NetWriter, ADescendingRangeIsWrittenAsARange) {
  const std::string net = "blocks:\n  a: {type: test/Constant, feedback: {property: value, from: 190, to: 10, step: 5, "
                          "search: coarse_to_fine, coarse_step: 30, fine_radius: 10, score: a.value}}\n";
  const std::string text = rewrite(net);
  EXPECT_NE(text.find("from: 190, to: 10, step: 5"), std::string::npos) << text;
  const FeedbackSpec f = *parseNetText(text, "t.yaml", "").blocks[0].feedback;
  ASSERT_EQ(f.values.size(), 37u) << text;
  EXPECT_EQ(f.values.front(), 190);
  EXPECT_EQ(f.values[1], 185);
  EXPECT_EQ(f.values.back(), 10);
}

TEST(NetWriter, SetTopLevelSectionReplacesOnlyThatSection) {
  const std::string text = "# head\nblocks:\n  a: {type: x}  # keep me\ndesigner:\n  positions: {a: [1, 2]}\n\n# tail\nlinks: []\n";
  const std::string replaced = setTopLevelSection(text, "designer", "positions: {a: [3, 4]}");
  EXPECT_EQ(replaced, "# head\nblocks:\n  a: {type: x}  # keep me\ndesigner:\n  positions: {a: [3, 4]}\n\n# tail\nlinks: []\n");
  EXPECT_EQ(setTopLevelSection(text, "designer", ""), "# head\nblocks:\n  a: {type: x}  # keep me\n\n# tail\nlinks: []\n");
  EXPECT_EQ(setTopLevelSection("blocks:\n  a: {type: x}\n\n", "designer", "positions: {}"),
            "blocks:\n  a: {type: x}\ndesigner:\n  positions: {}\n");
}

TEST(NetWriter, FormatNumberIsShortAndExact) {
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(40), "40");
  EXPECT_EQ(formatNumber(-2.5), "-2.5");
  EXPECT_EQ(std::stod(formatNumber(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(NetLoading, IgnoresTheDesignerSection) {
  const std::string net = std::string(kNet) + "designer:\n  positions: {a: [10, 20], b: [200, 20]}\n";
  const NetSpec spec = parseNetText(net, "t.yaml", "");
  EXPECT_EQ(spec.blocks.size(), 4u);
  EXPECT_NO_THROW(Net::build(spec));
}

TEST(NetLoading, UnknownTopLevelKeyStillNamesTheKnownOnes) {
  try {
    parseNetText("blocks:\n  a: {type: test/Constant}\ndesginer: {}\n", "t.yaml", "");
    FAIL() << "accepted an unknown key";
  } catch (const NetError& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml:3: unknown key 'desginer' (a net has blocks, links, doc and designer)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Graph, RenderDotMakesAnSvg) {
  const std::string svg = renderDot(toDot(*Net::build(parseNetText(kNet, "t.yaml", ""))), "svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("score"), std::string::npos);
  EXPECT_THROW(renderDot("digraph {", "svg"), std::runtime_error);
}
