#include "imagenets/registry.h"

#include <dlfcn.h>

#include <algorithm>
#include <stdexcept>


namespace imagenets {

BlockRegistry& BlockRegistry::instance() {
  static BlockRegistry registry;
  return registry;
}

void BlockRegistry::add(BlockInfo info, const void* anchor) {
  // A library loaded twice (linked, then again by a plug-in loader) registers the same names;
  // two different classes under one name is a mistake worth reporting.
  if (const BlockInfo* known = find(info.type)) {
    if (known->cpp_type != info.cpp_type) {
      conflicts_.push_back("block type '" + info.type + "' registered by both " + known->cpp_type + " and " +
                           info.cpp_type);
    }
    return;
  }
  Dl_info where{};
  if (anchor && dladdr(anchor, &where) && where.dli_fname) {
    std::string file = where.dli_fname;
    info.library = file.substr(file.find_last_of('/') + 1);
  }
  infos_.push_back(std::make_unique<BlockInfo>(std::move(info)));
}

const BlockInfo* BlockRegistry::findByTypeId(const std::type_info& cpp_type) const {
  for (const auto& info : infos_) {
    if (info->cpp_typeid && *info->cpp_typeid == cpp_type) return info.get();
  }
  return nullptr;
}

void BlockRegistry::addFormerName(const std::string& former, const std::string& type) {
  former_names_[former] = type;
}

const BlockInfo* BlockRegistry::find(const std::string& type) const {
  for (const auto& info : infos_) {
    if (info->type == type) return info.get();
  }
  auto former = former_names_.find(type);
  return former == former_names_.end() ? nullptr : find(former->second);
}

std::vector<const BlockInfo*> BlockRegistry::all() const {
  std::vector<const BlockInfo*> out;
  for (const auto& info : infos_) out.push_back(info.get());
  std::sort(out.begin(), out.end(), [](const BlockInfo* a, const BlockInfo* b) {
    return std::tie(a->category, a->type) < std::tie(b->category, b->type);
  });
  return out;
}

std::unique_ptr<Block> BlockRegistry::create(const std::string& type) const {
  const BlockInfo* info = find(type);
  if (!info) throw std::runtime_error("unknown block type '" + type + "'");
  std::unique_ptr<Block> block = info->create();
  block->setInfo(info);
  return block;
}

void BlockRegistry::setLibraryLoader(std::function<void()> loader) {
  if (!loader_) loader_ = std::move(loader);
}

const BlockInfo* BlockRegistry::findOrLoad(const std::string& type) {
  const BlockInfo* info = find(type);
  if (info) return info;
  loadLibraries();
  return find(type);
}

void BlockRegistry::loadLibraries() {
  if (loaded_ || !loader_) return;
  loaded_ = true;
  loader_();
}

namespace {
size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t above = row[j];
      bool same = std::tolower(a[i - 1]) == std::tolower(b[j - 1]);
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}
}  // namespace

std::vector<std::string> BlockRegistry::suggest(const std::string& type, size_t max) const {
  std::vector<std::pair<size_t, std::string>> scored;
  for (const auto& info : infos_) {
    // Compare with and without the "imagenets/" prefix, so "Treshold" finds "imagenets/Threshold".
    std::string bare = info->type.substr(info->type.find('/') + 1);
    scored.emplace_back(std::min(editDistance(type, info->type), editDistance(type, bare)), info->type);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> out;
  for (const auto& s : scored) {
    if (out.size() >= max || s.first > std::max<size_t>(3, type.size() / 2)) break;
    out.push_back(s.second);
  }
  return out;
}

}  // namespace imagenets
