// The block library's rooms: a category folder holds blocks only (each .cpp registers one, beside
// its test); what blocks share is in common/, and maths worth having without a block is in the
// library imagenets_vision/. A helper added beside the blocks fails here, naming the file.
#include <string>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "imagenets/testing/read_file.h"

namespace fs = boost::filesystem;

TEST(BlockLibraryLayout, EveryFileInACategoryFolderIsABlockOrItsTest) {
  const fs::path root(".");  // tests run in the package
  ASSERT_TRUE(fs::is_directory(root / "common")) << fs::absolute(root);
  int blocks = 0;
  for (fs::directory_iterator category(root), end; category != end; ++category) {
    const std::string name = category->path().filename().string();
    if (!fs::is_directory(category->path()) || name == "common" || name == "include" || name == "config" ||
        name == "launch" || name == "test")
      continue;
    for (fs::directory_iterator file(category->path()); file != end; ++file) {
      const std::string path = file->path().string();
      const std::string ext = file->path().extension().string();
      const std::string stem = file->path().stem().string();
      if (ext == ".h") {
        EXPECT_NE(stem.find("test_util"), std::string::npos)
            << path << ": a header beside the blocks; shared block helpers go in imagenets_blocks/common/";
        continue;
      }
      if (ext != ".cpp" || (stem.size() > 5 && stem.compare(stem.size() - 5, 5, "_test") == 0)) continue;
      EXPECT_NE(imagenets::testing::readFile(path).find("IMAGENETS_REGISTER_BLOCK("), std::string::npos)
          << path << " registers no block: library code goes in imagenets_vision/, block helpers in "
                     "imagenets_blocks/common/";
      ++blocks;
    }
  }
  EXPECT_GT(blocks, 50);  // the walk found the blocks at all
}
