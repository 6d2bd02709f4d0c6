// The committed nodelet_plugins.xml lists every block of libimagenets_calibration_blocks.
#include <gtest/gtest.h>

#include "imagenets/testing/plugin_xml_check.h"

TEST(PluginXml, CommittedFileMatchesTheRegistry) {
  imagenets::testing::expectPluginXmlCurrent("nodelet_plugins.xml", "imagenets_calibration_blocks");
}
