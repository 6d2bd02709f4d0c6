// The committed nodelet plug-in description must list every block of the installed libraries,
// spelled as IMAGENETS_REGISTER_BLOCK exports it: a new block without a regenerated file fails.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "imagenets/registry.h"

TEST(PluginXml, CommittedFileMatchesTheRegistry) {
  std::ifstream file("imagenets_plugins.xml");  // tests run in the repository root
  ASSERT_TRUE(file) << "imagenets_plugins.xml missing";
  std::stringstream committed;
  committed << file.rdbuf();
  EXPECT_EQ(committed.str(), imagenets::BlockRegistry::instance().pluginXml())
      << "imagenets_plugins.xml is out of date: run\n"
         "  devel/bin/imagenets blocks --plugin-xml > imagenets_plugins.xml";
}

TEST(PluginXml, ListsEveryBlockOfTheBlockLibrary) {
  const std::string xml = imagenets::BlockRegistry::instance().pluginXml();
  for (const imagenets::BlockInfo* info : imagenets::BlockRegistry::instance().all()) {
    if (info->library != "libimagenets_blocks.so") continue;
    EXPECT_NE(xml.find("<class name=\"" + info->type + "\""), std::string::npos) << info->type;
  }
  EXPECT_NE(xml.find("<library path=\"lib/libimagenets_blocks\">"), std::string::npos);
  EXPECT_NE(xml.find("imagenets::BlockNodelet&lt;imagenets::blocks::Threshold&gt;"), std::string::npos);
}
