// The engine's own blocks (sub-nets, net ports) are exported by the nodelet layer, the engine
// knows no nodelets: the committed nodelet_plugins.xml lists them for libimagenets_nodelet.
#include <gtest/gtest.h>

#include "imagenets/testing/plugin_xml_check.h"

TEST(PluginXml, CommittedFileListsTheEnginesBlocks) {
  imagenets::testing::expectPluginXmlCurrent("nodelet_plugins.xml", "imagenets_nodelet");  // tests run in the package
  const std::string xml = imagenets::nodeletPluginXml("imagenets_nodelet");
  EXPECT_NE(xml.find("imagenets::BlockNodelet&lt;imagenets::SubNetBlock&gt;"), std::string::npos);
  EXPECT_EQ(xml.find("lib/libimagenets_core\""), std::string::npos);
}
