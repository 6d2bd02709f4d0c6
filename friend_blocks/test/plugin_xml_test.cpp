// The committed nodelet_plugins.xml lists every block of libfriend_blocks.
#include <gtest/gtest.h>

#include "imagenets/testing/plugin_xml_check.h"

TEST(PluginXml, CommittedFileMatchesTheRegistry) {
  imagenets::testing::expectPluginXmlCurrent("nodelet_plugins.xml", "friend_blocks");  // tests run in the package
  const std::string xml = imagenets::nodeletPluginXml("friend_blocks");
  for (const char* type : {"imagenets/MoveArm", "imagenets/MoveHead", "imagenets/WorldModelGet", "imagenets/WorldModelSet"}) {
    EXPECT_NE(xml.find(std::string("<class name=\"") + type + "\""), std::string::npos) << type;
  }
}
