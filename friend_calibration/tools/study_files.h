// What the studies of the command line tool (repeatability, accuracy-study) share: writing their
// files so that a reader never sees half of one, quoting CSV text, and reading count lists.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace imagenets {
namespace tool {

// Writes `text` (or the picture, as PNG) to `path` through a temporary file and a rename.
// Throws std::runtime_error naming the file when it cannot be written.
void writeFileAtomically(const std::string& path, const std::string& text);
void writePngAtomically(const std::string& path, const cv::Mat& picture);

// A CSV field for free text: in double quotes, inner double quotes made single.
std::string csvQuoted(std::string text);

// "1,3,5" -> {1, 3, 5}; throws UsageError naming `flag` and the item unless every item is a
// count 1..999.
std::vector<int> parseCounts(const std::string& flag, const std::string& list);

}  // namespace tool
}  // namespace imagenets
