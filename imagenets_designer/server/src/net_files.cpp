#include "net_files.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <boost/filesystem.hpp>

#include "request_error.h"

namespace imagenets {
namespace designer {

namespace fs = boost::filesystem;

std::string NetFiles::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw NetError({path + ": cannot read net file: " + std::strerror(errno)});
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

NetDocument NetFiles::load(const std::string& path) const {
  return NetDocument::fromText(read(path), path, fs::path(path).parent_path().string());
}

NetFiles::Saved NetFiles::save(const NetDocument& doc, const std::string& path) const {
  NetDocument next = doc;
  next.moveTo(path, fs::path(path).parent_path().string());
  const std::string text = next.text();
  // An empty net is refused here too.
  parseNetText(text, path, next.spec.base_dir);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << text;
    if (!out.flush()) throw RequestError("cannot write '" + tmp + "': " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw RequestError("cannot write '" + path + "': " + std::strerror(errno));
  }
  next.rebase(text);
  return {std::move(next), text};
}

nlohmann::json NetFiles::list(const std::string& dir) const {
  if (!fs::is_directory(dir)) throw RequestError("'" + dir + "' is not a folder");
  std::vector<std::pair<bool, std::string>> entries;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    entries.emplace_back(!fs::is_directory(e.path()), name);
  }
  std::sort(entries.begin(), entries.end());
  nlohmann::json list = nlohmann::json::array();
  for (const auto& [file, name] : entries) list.push_back({{"name", name}, {"dir", !file}});
  return {{"dir", dir}, {"entries", list}, {"roots", roots_.roots()}};
}

}  // namespace designer
}  // namespace imagenets
