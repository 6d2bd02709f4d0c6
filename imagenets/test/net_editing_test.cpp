// The operations tools use to edit a net: on its spec (find a block, set or drop a property,
// remove a block) and on a running executor (several properties at once, the block configured
// anew, and whether the net must be built anew because its ports changed).
#include <gtest/gtest.h>
#include <std_msgs/Float64.h>

#include "imagenets/executor.h"
#include "imagenets/registry.h"
#include "test_blocks.h"

using namespace imagenets;

namespace {

const char* kNet = R"(
blocks:
  a: {type: test/Constant, properties: {value: 2}}
  b: {type: test/Scale, properties: {gain: 3}}
  p: {type: test/Parabola}
  t:
    type: test/Constant
    feedback: {property: value, from: 0, to: 4, score: p.score, initial: [a.value]}
links:
  - a.value -> b.in
  - t.value -> p.x
)";

// A sub-net with one output port: the net inside decides the block's ports.
std::string subNet(const std::string& gain, const std::string& port = "y") {
  return "blocks:\n"
         "  c: {type: test/Constant, properties: {value: 2}}\n"
         "  s: {type: test/Scale, properties: {gain: " + gain + "}}\n"
         "  out: {type: imagenets/SubNetOutput, properties: {port: " + port + ", type: std_msgs/Float64}}\n"
         "links: [c.value -> s.in, s.out -> out.value]\n";
}

std::unique_ptr<Executor> withSubNet() {
  NetSpec spec = parseNetText("blocks:\n  sub: {type: imagenets/SubNet}\n", "outer.yaml", "");
  spec.block("sub").setProperty("net_yaml", subNet("3"));
  return std::make_unique<Executor>(Net::build(spec), ExecutorOptions{2});
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(NetSpecEditing, FindsBlocksByNameAndNamesTheMissingOne) {
  NetSpec spec = parseNetText(kNet, "test.yaml", "");
  ASSERT_NE(spec.findBlock("b"), nullptr);
  EXPECT_EQ(spec.findBlock("b")->type, "test/Scale");
  EXPECT_EQ(spec.findBlock("zz"), nullptr);
  EXPECT_EQ(&spec.block("a"), spec.findBlock("a"));
  EXPECT_EQ(errorOf([&] { spec.block("zz"); }), "test.yaml: no block named 'zz'");
}

TEST(NetSpecEditing, SetsReplacesAndDropsPropertySettings) {
  NetSpec spec = parseNetText(kNet, "test.yaml", "");
  BlockSpec& b = spec.block("b");
  b.setProperty("gain", "5");
  b.setProperty("offset", "1");
  ASSERT_EQ(b.properties.size(), 2u);  // replaced, then added
  EXPECT_EQ(b.findSetting("gain")->text, "5");
  EXPECT_EQ(b.findSetting("offset")->loc.str(), b.loc.str());  // where the block is written
  EXPECT_TRUE(b.removeProperty("gain"));
  EXPECT_FALSE(b.removeProperty("gain"));
  EXPECT_EQ(b.findSetting("gain"), nullptr);
  auto e = Executor(Net::build(spec));
  e.run();
  EXPECT_DOUBLE_EQ(e.output<std_msgs::Float64>("b.out")->data, 3.0);  // 2 * default gain 1 + 1
}

TEST(NetSpecEditing, RemovingABlockTakesWhatRefersToIt) {
  NetSpec spec = parseNetText(kNet, "test.yaml", "");
  EXPECT_TRUE(spec.removeBlock("a"));
  EXPECT_EQ(spec.findBlock("a"), nullptr);
  EXPECT_EQ(spec.links.size(), 1u);                       // a.value -> b.in is gone
  EXPECT_TRUE(spec.block("t").feedback->initial.empty());  // so is the initial value from a
  EXPECT_TRUE(spec.removeBlock("p"));
  EXPECT_FALSE(spec.block("t").feedback);  // scored by p: gone with it
  EXPECT_TRUE(spec.links.empty());
  EXPECT_FALSE(spec.removeBlock("p"));
}

TEST(BlockProperties, ParsingNamesUnknownPropertiesAndBadValues) {
  auto scale = BlockRegistry::instance().create("test/Scale");
  EXPECT_EQ(std::get<double>(scale->parseProperty("gain", "2.5")), 2.5);
  EXPECT_EQ(errorOf([&] { scale->parseProperty("gian", "2"); }), "unknown property 'gian' (known: gain, offset, fail)");
  EXPECT_EQ(errorOf([&] { scale->parseProperty("gain", "lots"); }), "property 'gain': expected double, got 'lots'");
  EXPECT_EQ(errorOf([&] { scale->setProperty("gian", 2.0); }), "unknown property 'gian' (known: gain, offset, fail)");
}

TEST(ExecutorEditing, SetsSeveralPropertiesOfABlockAtOnce) {
  Executor e(Net::build(parseNetText(kNet, "test.yaml", "")));
  e.run();
  EXPECT_EQ(e.setProperties("b", {{"gain", 10.0}, {"offset", 1}}), Executor::PropertyChange::Applied);
  EXPECT_EQ(e.run().ran, (std::vector<std::string>{"b"}));
  EXPECT_DOUBLE_EQ(e.output<std_msgs::Float64>("b.out")->data, 21.0);
}

TEST(ExecutorEditing, AnInvalidValueChangesNothingAndIsNamed) {
  Executor e(Net::build(parseNetText(kNet, "test.yaml", "")));
  e.run();
  const std::string range = errorOf([&] { e.setProperties("b", {{"gain", 10.0}, {"offset", 5000}}); });
  EXPECT_EQ(range.rfind("test.yaml: block 'b': property 'offset': value 5000 is out of range [", 0), 0u) << range;
  EXPECT_EQ(errorOf([&] { e.setProperties("b", {{"gian", 10.0}}); }),
            "test.yaml: block 'b': unknown property 'gian' (known: gain, offset, fail)");
  EXPECT_EQ(errorOf([&] { e.setProperties("zz", {{"gain", 10.0}}); }), "test.yaml: no block named 'zz'");
  EXPECT_EQ(errorOf([&] { e.setPropertyText("b", "gain", "lots"); }),
            "test.yaml: block 'b': property 'gain': expected double, got 'lots'");
  EXPECT_TRUE(e.run().ran.empty());  // nothing changed, nothing out of date
  EXPECT_DOUBLE_EQ(e.output<std_msgs::Float64>("b.out")->data, 6.0);
}

TEST(ExecutorEditing, AChangeReachesWhatConfigureReads) {
  auto e = withSubNet();
  e->run();
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 6.0);
  // The sub-net is loaded in configure(): the block is configured anew with the new net.
  EXPECT_EQ(e->setProperties("sub", {{"net_yaml", subNet("5")}}), Executor::PropertyChange::Applied);
  e->run();
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 10.0);
}

TEST(ExecutorEditing, SaysWhenPortsChangeAndChangesNothing) {
  auto e = withSubNet();
  e->run();
  EXPECT_EQ(e->setProperties("sub", {{"net_yaml", subNet("5", "z")}}),
            Executor::PropertyChange::NeedsRebuild);
  EXPECT_EQ(e->net().node(0).block->outputs()[0].name, "y");
  EXPECT_TRUE(e->run().ran.empty());
  EXPECT_DOUBLE_EQ(e->output<std_msgs::Float64>("sub.y")->data, 6.0);
  const std::string error = errorOf([&] { e->setPropertyText("sub", "net_yaml", subNet("5", "z")); });
  EXPECT_NE(error.find("outer.yaml: block 'sub': property 'net_yaml': "), std::string::npos) << error;
  EXPECT_NE(error.find("changes the block's ports; build the net anew with it"), std::string::npos) << error;
}

TEST(ExecutorEditing, AValueConfigureRefusesIsNamedAndChangesNothing) {
  auto e = withSubNet();
  e->run();
  const std::string error = errorOf([&] { e->setProperties("sub", {{"net_yaml", std::string("blocks: {x: {type: test/Nope}}")}}); });
  EXPECT_EQ(error.rfind("outer.yaml: block 'sub': ", 0), 0u) << error;
  EXPECT_NE(error.find("unknown block type 'test/Nope'"), std::string::npos) << error;
  EXPECT_TRUE(e->run().ran.empty());
}
