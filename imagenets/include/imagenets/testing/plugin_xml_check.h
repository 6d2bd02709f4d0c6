// For each package's test: its committed nodelet_plugins.xml must list every block its library
// exports, as IMAGENETS_REGISTER_BLOCK / IMAGENETS_EXPORT_BLOCK_NODELET spell them; a new block
// without a regenerated file fails. Call from a test that links the library.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "imagenets/nodelet_plugins.h"

namespace imagenets {
namespace testing {

// `file`: the package's nodelet_plugins.xml; `library`: e.g. "imagenets_blocks".
inline void expectPluginXmlCurrent(const std::string& file, const std::string& library) {
  std::ifstream in(file);
  ASSERT_TRUE(in) << file << " missing";
  std::stringstream committed;
  committed << in.rdbuf();
  EXPECT_EQ(committed.str(), nodeletPluginXml(library))
      << file << " is out of date: run\n  imagenets blocks --plugin-xml --library " << library << " > /tmp/x && mv /tmp/x "
      << file;
}

}  // namespace testing
}  // namespace imagenets
