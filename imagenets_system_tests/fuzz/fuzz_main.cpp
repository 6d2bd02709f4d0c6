// libFuzzer entry point (the `imagenets_fuzz` executable of a clang build with -DIMAGENETS_FUZZ=ON,
// run by scripts/fuzz): IMAGENETS_FUZZ_TARGET names the target (fuzz_targets.h), or is `list` to print
// "NAME SEEDS" per target. Each input goes to a file, as the parsers read files in use, then to the
// target's parser. An exception is a refusal, the expected answer to bad input; a crash, a
// sanitizer report or a hang is a finding.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>

#include "fuzz_targets.h"

namespace {

const imagenets::fuzz::Target* target = nullptr;

struct InputFile {
  // In memory (/dev/shm) when possible; one per process, removed at exit.
  std::string path = std::string(access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") + "/imagenets_fuzz_" +
                     std::to_string(getpid()) + ".yaml";
  ~InputFile() { std::remove(path.c_str()); }
};

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* name = std::getenv("IMAGENETS_FUZZ_TARGET");
  if (name && std::string(name) == "list") {
    for (const auto& t : imagenets::fuzz::targets()) std::cout << t.name << " " << t.seeds << "\n";
    std::exit(0);
  }
  try {
    target = &imagenets::fuzz::target(name ? name : "");
  } catch (const std::exception& e) {
    std::cerr << "imagenets_fuzz: set IMAGENETS_FUZZ_TARGET to a target (or `list`): " << e.what() << "\n";
    std::exit(2);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const InputFile file;
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::ofstream(file.path, std::ios::binary | std::ios::trunc) << input;
  try {
    target->parse(input, file.path);
  } catch (const std::exception&) {
  }
  return 0;
}
