// The committed nodelet_plugins.xml lists every block of libimagenets_blocks.
#include <gtest/gtest.h>

#include "imagenets/registry.h"
#include "imagenets/testing/plugin_xml_check.h"

TEST(PluginXml, CommittedFileMatchesTheRegistry) {
  imagenets::testing::expectPluginXmlCurrent("nodelet_plugins.xml", "imagenets_blocks");  // tests run in the package
}

TEST(PluginXml, ListsEveryBlockOfTheBlockLibrary) {
  const std::string xml = imagenets::nodeletPluginXml("imagenets_blocks");
  for (const imagenets::BlockInfo* info : imagenets::BlockRegistry::instance().all()) {
    if (info->library != "libimagenets_blocks.so") continue;
    EXPECT_NE(xml.find("<class name=\"" + info->type + "\""), std::string::npos) << info->type;
  }
  EXPECT_NE(xml.find("<library path=\"lib/libimagenets_blocks\">"), std::string::npos);
  EXPECT_NE(xml.find("imagenets::BlockNodelet&lt;imagenets::blocks::Threshold&gt;"), std::string::npos);
  // Only this library: the engine's own blocks are in the imagenets package's file.
  EXPECT_EQ(xml.find("lib/libimagenets_nodelet\""), std::string::npos);
}
