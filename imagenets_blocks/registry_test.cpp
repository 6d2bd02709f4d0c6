#include <gtest/gtest.h>

#include "imagenets/registry.h"

// Every block type name belongs to exactly one class (a second registration would be ignored).
TEST(Registry, NoTwoBlocksShareATypeName) {
  for (const auto& conflict : imagenets::BlockRegistry::instance().conflicts()) ADD_FAILURE() << conflict;
  EXPECT_GT(imagenets::BlockRegistry::instance().all().size(), 40u);
}
