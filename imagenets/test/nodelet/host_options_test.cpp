// The nodelet host's own settings: not block properties, declared like them, hidden by a block
// property of the same name; the ones that cannot change live say so (no name is special-cased).
#include <gtest/gtest.h>

#include "../../src/nodelet/host_options.h"

namespace imagenets {
namespace {

class Plain : public Block {
 public:
  void process(Context&) override {}
};

// A block with a property named like a host setting.
class OwnsLatch : public Block {
 public:
  OwnsLatch() { addProperty<bool>("latch", true, "the block's own"); }
  void process(Context&) override {}
};

std::vector<std::string> names(const HostOptions& o) {
  std::vector<std::string> out;
  for (const auto& s : o.specs()) out.push_back(s.name());
  return out;
}

TEST(HostOptions, DefaultsAndWhichCannotChangeLive) {
  Plain block;
  HostOptions o(block, false);
  EXPECT_EQ(names(o), (std::vector<std::string>{"pairing", "pairing_slop", "queue_size", "latch", "source_mode",
                                                "source_rate"}));
  EXPECT_TRUE(o.find("latch")->isFixedAtLoad());
  EXPECT_TRUE(o.find("queue_size")->isFixedAtLoad());
  EXPECT_FALSE(o.find("source_mode")->isFixedAtLoad());
  EXPECT_EQ(o.queueSize(), 5u);
  EXPECT_FALSE(o.latch());
  EXPECT_FALSE(o.publishInternalPorts());
  EXPECT_TRUE(block.propertySpecs().empty());  // nothing was added to the block
}

TEST(HostOptions, SetIsCheckedAndFeedsThePairing) {
  Plain block;
  HostOptions o(block, false);
  o.set("pairing", std::string("approximate"));
  o.set("pairing_slop", 0.2);
  EXPECT_TRUE(o.pairing().approximate);
  EXPECT_DOUBLE_EQ(o.pairing().slop, 0.2);
  EXPECT_THROW(o.set("pairing", std::string("sideways")), PropertyError);
  EXPECT_THROW(o.set("queue_size", 0), PropertyError);
  EXPECT_THROW(o.set("nope", 1), PropertyError);
}

TEST(HostOptions, ABlockPropertyHidesTheHostsAndInnerNetsGetTheirPortsOption) {
  OwnsLatch owns;
  HostOptions hidden(owns, true);
  EXPECT_FALSE(hidden.find("latch"));
  EXPECT_FALSE(hidden.latch());  // the host's default, not the block's value
  ASSERT_TRUE(hidden.find("publish_internal_ports"));
  hidden.set("publish_internal_ports", true);
  EXPECT_TRUE(hidden.publishInternalPorts());
}

}  // namespace
}  // namespace imagenets
