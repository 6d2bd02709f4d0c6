// The block registry: every block type by name ("imagenets/Threshold"), with its category and
// one-line doc. IMAGENETS_REGISTER_BLOCK is the one line a block's .cpp adds to be found by nets,
// by the `imagenets blocks` browser and by the nodelet host.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "imagenets/block.h"

namespace imagenets {

struct BlockInfo {
  std::string type;      // "imagenets/Threshold"
  std::string cpp_type;  // "imagenets::blocks::Threshold"
  std::string category;  // "segmentation"
  std::string doc;       // one line
  std::function<std::unique_ptr<Block>()> create;
};

class BlockRegistry {
 public:
  static BlockRegistry& instance();

  void add(BlockInfo info);
  const BlockInfo* find(const std::string& type) const;
  std::vector<const BlockInfo*> all() const;  // sorted by category, then type
  // Creates a block with its info set; throws std::runtime_error for an unknown type.
  std::unique_ptr<Block> create(const std::string& type) const;
  // Known types closest to an unknown name (edit distance), best first.
  std::vector<std::string> suggest(const std::string& type, size_t max = 3) const;

 private:
  std::vector<std::unique_ptr<BlockInfo>> infos_;
};

namespace detail {
struct BlockRegistration {
  BlockRegistration(BlockInfo info) { BlockRegistry::instance().add(std::move(info)); }
};
}  // namespace detail

}  // namespace imagenets

#define IMAGENETS_DETAIL_CAT2(a, b) a##b
#define IMAGENETS_DETAIL_CAT(a, b) IMAGENETS_DETAIL_CAT2(a, b)

// Registers Class (default-constructible, derived from imagenets::Block) under TypeName.
#define IMAGENETS_REGISTER_BLOCK(Class, TypeName, Category, Doc)                                \
  static ::imagenets::detail::BlockRegistration IMAGENETS_DETAIL_CAT(imagenets_block_reg_,      \
                                                                     __LINE__)(                 \
      ::imagenets::BlockInfo{TypeName, #Class, Category, Doc,                                    \
                             []() -> std::unique_ptr<::imagenets::Block> {                       \
                               return std::make_unique<Class>();                                 \
                             }})
