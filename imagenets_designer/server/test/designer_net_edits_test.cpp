// The edits of a net as functions from document to document, without an executor: each leaves
// its input as it was (undo keeps it) and carries names through links, feedback and positions.
#include <functional>

#include <gtest/gtest.h>

#include "edit_history.h"
#include "net_edits.h"

using namespace imagenets;
using namespace imagenets::designer;

namespace {

const char* kNet = R"(blocks:
  source: {type: imagenets/ImageFileSource, properties: {path: scene.png}}
  gray: {type: imagenets/Grayscale}
  threshold:
    type: imagenets/Threshold
    feedback: {property: threshold, from: 40, to: 80, step: 5, score: detector.confidence, initial: [60, otsu.threshold]}
  otsu: {type: imagenets/Threshold}
  detector: {type: imagenets/MarkerDetector}
links:
  - source.image -> gray.image
  - gray.image -> threshold.image
  - threshold.image -> detector.image
designer: {positions: {source: [0, 0], gray: [200, 0]}}
)";

NetDocument net() { return NetDocument::fromText(kNet, "/nets/demo.yaml", "/nets"); }

std::vector<std::string> links(const NetDocument& doc) {
  std::vector<std::string> out;
  for (const auto& l : doc.spec.links) out.push_back(l.from_block + "." + l.from_port + " -> " + l.to_block + "." + l.to_port);
  return out;
}

std::string errorOf(const std::function<void()>& edit) {
  try {
    edit();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(NetEdits, AddBlockLeavesTheInputAsItWas) {
  const NetDocument before = net();
  BlockSpec b;
  b.name = edits::freeName(before, edits::nameFromType("imagenets/GaussianBlur"));
  b.type = "imagenets/GaussianBlur";
  const NetDocument after = edits::addBlock(before, b, edits::Position{10, 20});
  EXPECT_EQ(b.name, "gaussian_blur");
  ASSERT_NE(after.spec.findBlock("gaussian_blur"), nullptr);
  EXPECT_EQ(after.positions.at("gaussian_blur"), (edits::Position{10, 20}));
  EXPECT_EQ(before.spec.findBlock("gaussian_blur"), nullptr);
  EXPECT_EQ(before.spec.blocks.size() + 1, after.spec.blocks.size());
}

TEST(NetEdits, NamesFromTypesAreSnakeCaseAndFree) {
  EXPECT_EQ(edits::nameFromType("imagenets/ImageFileSource"), "image_file_source");
  EXPECT_EQ(edits::nameFromType("imagenets/"), "block");
  EXPECT_EQ(edits::freeName(net(), "gray"), "gray_2");
  EXPECT_EQ(edits::freeName(net(), "gray", {"gray_2"}), "gray_3");
  EXPECT_EQ(edits::freeName(net(), "blur"), "blur");
}

TEST(NetEdits, RemovingBlocksTakesTheirLinksPositionsAndFeedbackReferences) {
  const NetDocument before = net();
  NetDocument after = edits::removeBlocks(before, {"gray", "otsu"});
  EXPECT_EQ(after.spec.findBlock("gray"), nullptr);
  EXPECT_EQ(links(after), std::vector<std::string>{"threshold.image -> detector.image"});
  EXPECT_EQ(after.positions.count("gray"), 0u);
  // The initial value read from otsu goes; the constant stays, and so does the feedback.
  ASSERT_TRUE(after.spec.findBlock("threshold")->feedback);
  ASSERT_EQ(after.spec.findBlock("threshold")->feedback->initial.size(), 1u);
  EXPECT_EQ(after.spec.findBlock("threshold")->feedback->initial[0].str(), "60");
  // A feedback scored by a removed block goes with it.
  after = edits::removeBlocks(after, {"detector"});
  EXPECT_FALSE(after.spec.findBlock("threshold")->feedback);
  EXPECT_EQ(links(before).size(), 3u);

  EXPECT_EQ(errorOf([&] { edits::removeBlocks(before, {"gray", "nope"}); }), "no block named 'nope'");
}

TEST(NetEdits, MovingNeedsTheBlock) {
  const NetDocument after = edits::moveBlocks(net(), {{"detector", {5, 6}}});
  EXPECT_EQ(after.positions.at("detector"), (edits::Position{5, 6}));
  EXPECT_EQ(errorOf([] { edits::moveBlocks(net(), {{"nope", {0, 0}}}); }), "no block named 'nope'");
}

TEST(NetEdits, LinksAreAddedAndRemovedByTheirEndpoints) {
  const NetDocument added = edits::addLink(net(), "source.image", "otsu.image");
  EXPECT_EQ(links(added).back(), "source.image -> otsu.image");
  EXPECT_EQ(links(edits::removeLink(added, "source.image", "otsu.image")), links(net()));
  EXPECT_EQ(errorOf([] { edits::addLink(net(), "source", "otsu.image"); }), "'from' 'source' is not of the form block.port");
  EXPECT_EQ(errorOf([] { edits::addLink(net(), "source.image", "otsu."); }), "'to' 'otsu.' is not of the form block.port");
  EXPECT_EQ(errorOf([] { edits::removeLink(net(), "gray.image", "otsu.image"); }), "no link gray.image -> otsu.image");
}

TEST(NetEdits, APropertyIsSetChangedAndBackToItsDefault) {
  const NetDocument set = edits::setProperty(net(), "otsu", "threshold", std::string("90"));
  ASSERT_EQ(set.spec.findBlock("otsu")->properties.size(), 1u);
  EXPECT_EQ(set.spec.findBlock("otsu")->properties[0].text, "90");
  const NetDocument changed = edits::setProperty(set, "otsu", "threshold", std::string("95"));
  ASSERT_EQ(changed.spec.findBlock("otsu")->properties.size(), 1u);
  EXPECT_EQ(changed.spec.findBlock("otsu")->properties[0].text, "95");
  EXPECT_EQ(set.spec.findBlock("otsu")->properties[0].text, "90");
  EXPECT_TRUE(edits::setProperty(changed, "otsu", "threshold", std::nullopt).spec.findBlock("otsu")->properties.empty());
  // Whether the property exists is the engine's to say when the net is built.
  EXPECT_EQ(errorOf([] { edits::setProperty(net(), "nope", "x", std::string("1")); }), "no block named 'nope'");
}

TEST(NetEdits, RenamingCarriesTheNameThroughLinksFeedbackAndPosition) {
  const NetDocument before = net();
  NetDocument after = edits::renameBlock(before, "detector", "det");
  EXPECT_EQ(links(after).back(), "threshold.image -> det.image");
  EXPECT_EQ(after.spec.findBlock("threshold")->feedback->score_block, "det");
  after = edits::renameBlock(after, "otsu", "o");
  EXPECT_EQ(after.spec.findBlock("threshold")->feedback->initial[1].str(), "o.threshold");
  after = edits::renameBlock(after, "gray", "g");
  EXPECT_EQ(after.positions.count("gray"), 0u);
  EXPECT_EQ(after.positions.at("g"), (edits::Position{200, 0}));
  EXPECT_EQ(before.spec.findBlock("threshold")->feedback->score_block, "detector");
  EXPECT_EQ(errorOf([&] { edits::renameBlock(before, "gray", "source"); }), "a block named 'source' exists already");
}

TEST(NetEdits, PasteMakesNamesUniqueAndRenamesItsLinksAndFeedback) {
  const NetDocument before = net();
  std::vector<edits::PastedBlock> blocks(2);
  blocks[0].spec = *before.spec.findBlock("threshold");
  blocks[0].position = edits::Position{1, 2};
  blocks[1].spec = *before.spec.findBlock("detector");
  const edits::Pasted pasted =
      edits::paste(before, blocks, {{"threshold.image", "detector.image"}, {"gray.image", "threshold.image"}});
  EXPECT_EQ(pasted.names.at("threshold"), "threshold_2");
  EXPECT_EQ(pasted.names.at("detector"), "detector_2");
  const std::vector<std::string> all = links(pasted.doc);
  // Links between pasted blocks follow both; a link from a block of the net keeps that block.
  EXPECT_EQ(all[all.size() - 2], "threshold_2.image -> detector_2.image");
  EXPECT_EQ(all.back(), "gray.image -> threshold_2.image");
  const BlockSpec& copy = *pasted.doc.spec.findBlock("threshold_2");
  EXPECT_EQ(copy.feedback->score_block, "detector_2");
  EXPECT_EQ(copy.feedback->initial[1].str(), "otsu.threshold");  // otsu was not pasted
  EXPECT_EQ(pasted.doc.positions.at("threshold_2"), (edits::Position{1, 2}));
  EXPECT_EQ(pasted.doc.positions.count("detector_2"), 0u);
  EXPECT_EQ(before.spec.blocks.size() + 2, pasted.doc.spec.blocks.size());
}

TEST(NetEdits, TextReplacesTheNetAndKeepsThePositionsOfBlocksThatStay) {
  const NetDocument after = edits::setText(net(), "blocks:\n  gray: {type: imagenets/Grayscale}\n");
  EXPECT_EQ(after.spec.blocks.size(), 1u);
  EXPECT_EQ(after.positions.at("gray"), (edits::Position{200, 0}));
  EXPECT_EQ(after.positions.count("source"), 0u);
  EXPECT_EQ(after.spec.origin, "/nets/demo.yaml");
  EXPECT_THROW(edits::setText(net(), "blocks:\n  gray: [\n"), NetError);
}

TEST(EditHistory, MergedEditsAreOneStepAndANewEditDropsTheRedos) {
  EditHistory history;
  EXPECT_EQ(errorOf([&] { history.target(EditHistory::Direction::Undo); }), "nothing to undo");
  const NetDocument a = net();
  const NetDocument b = edits::setProperty(a, "otsu", "threshold", std::string("1"));
  const NetDocument c = edits::setProperty(b, "otsu", "threshold", std::string("2"));
  history.edited(a, "otsu.threshold");
  history.edited(b, "otsu.threshold");  // the same slider: still one step back to `a`
  ASSERT_TRUE(history.canUndo());
  EXPECT_TRUE(history.target(EditHistory::Direction::Undo).sameNet(a));
  history.stepped(EditHistory::Direction::Undo, c);
  EXPECT_FALSE(history.canUndo());
  ASSERT_TRUE(history.canRedo());
  EXPECT_TRUE(history.target(EditHistory::Direction::Redo).sameNet(c));
  history.edited(a);
  EXPECT_FALSE(history.canRedo());
  EXPECT_EQ(errorOf([&] { history.target(EditHistory::Direction::Redo); }), "nothing to redo");
}
