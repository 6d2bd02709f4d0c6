// Every input the fuzzers found a fault with (test/fuzz/regressions/TARGET/*) goes once more to the
// parser it broke: it must now be refused with an error that names the file (or be accepted), and
// nothing may crash. Run by `make test`; the fuzzers themselves run with `make fuzz`.
#include <cstdlib>

#include <boost/filesystem.hpp>
#include <gtest/gtest.h>

#include "fuzz_targets.h"
#include "imagenets/testing/read_file.h"

namespace fs = boost::filesystem;

TEST(FuzzRegressions, EveryFoundInputIsRefusedWithANamedErrorOrAccepted) {
  // IMAGENETS_FUZZ_INPUTS=out/fuzz/corpus checks a whole fuzzing corpus the same way (triage).
  const char* other = std::getenv("IMAGENETS_FUZZ_INPUTS");
  const fs::path root = other ? fs::path(other) : fs::path(IMAGENETS_SOURCE_DIR) / "fuzz/regressions";
  ASSERT_TRUE(fs::is_directory(root)) << root;
  int cases = 0;
  for (const auto& dir : fs::directory_iterator(root)) {
    if (!fs::is_directory(dir.path())) continue;
    const auto& target = imagenets::fuzz::target(dir.path().filename().string());  // a folder per target
    for (const auto& entry : fs::directory_iterator(dir.path())) {
      const std::string file = entry.path().string();
      const std::string input = imagenets::testing::readFile(file);
      ++cases;
      try {
        target.parse(input, file);
      } catch (const std::exception& e) {
        const std::string what = e.what();
        EXPECT_FALSE(what.empty()) << target.name << ": " << file;
        if (target.reads_file) EXPECT_NE(what.find(file), std::string::npos) << target.name << " " << file << ": " << what;
      }
    }
  }
  EXPECT_GT(cases, 0) << "no regression input under " << root;
}
