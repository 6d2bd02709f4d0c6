#include "study_files.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "imagenets/tool/command.h"

namespace imagenets {
namespace tool {

void writeFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << text;
    if (!f) throw std::runtime_error("cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

void writePngAtomically(const std::string& path, const cv::Mat& picture) {
  const std::string tmp = path + ".tmp.png";
  if (!cv::imwrite(tmp, picture)) throw std::runtime_error("cannot write " + tmp);
  std::filesystem::rename(tmp, path);
}

std::string csvQuoted(std::string text) {
  for (char& c : text) {
    if (c == '"') c = '\'';
  }
  return '"' + text + '"';
}

std::vector<int> parseCounts(const std::string& flag, const std::string& list) {
  std::vector<int> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const long n = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end || n < 1 || n > 999) {
      throw UsageError(flag + " '" + list + "': '" + item + "' is not a count 1..999");
    }
    out.push_back(static_cast<int>(n));
  }
  if (out.empty()) throw UsageError(flag + " needs a list like 1,3,5");
  return out;
}

}  // namespace tool
}  // namespace imagenets
