// The block registry: every block type by name ("imagenets/Threshold"), with its category and
// one-line doc. IMAGENETS_REGISTER_BLOCK is the one line a block's .cpp adds to be found by nets,
// by the `imagenets blocks` browser and by the nodelet host.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include <pluginlib/class_list_macros.hpp>

#include "imagenets/block.h"
#include "imagenets/block_nodelet.h"

namespace imagenets {

struct BlockInfo {
  std::string type;      // "imagenets/Threshold"
  std::string cpp_type;  // "imagenets::blocks::Threshold"
  std::string category;  // "segmentation"
  std::string doc;       // one line
  std::function<std::unique_ptr<Block>()> create;
  const std::type_info* cpp_typeid = nullptr;  // lets the nodelet host find its block's info
  // File name of the shared object that registered the block ("libimagenets_blocks.so"); the
  // executable's name for blocks linked into a program. Set by the registry.
  std::string library;
};

class BlockRegistry {
 public:
  static BlockRegistry& instance();

  // `anchor`: any object inside the registering binary (tells which library it is).
  void add(BlockInfo info, const void* anchor = nullptr);
  const BlockInfo* find(const std::string& type) const;
  const BlockInfo* findByTypeId(const std::type_info& cpp_type) const;
  std::vector<const BlockInfo*> all() const;  // sorted by category, then type
  // Creates a block with its info set; throws std::runtime_error for an unknown type.
  std::unique_ptr<Block> create(const std::string& type) const;
  // The nodelet plug-in description (imagenets_plugins.xml): one <library> per installed library
  // that registers blocks (libimagenets_core, libimagenets_blocks; test code and programs are
  // left out). Printed by `imagenets blocks --plugin-xml`; a test checks the committed file.
  std::string pluginXml() const;
  // Known types closest to an unknown name (edit distance), best first.
  std::vector<std::string> suggest(const std::string& type, size_t max = 3) const;
  // Type names claimed by two different classes (the first one wins); should be empty.
  const std::vector<std::string>& conflicts() const { return conflicts_; }

 private:
  std::vector<std::unique_ptr<BlockInfo>> infos_;
  std::vector<std::string> conflicts_;
};

namespace detail {
struct BlockRegistration {
  BlockRegistration(BlockInfo info) { BlockRegistry::instance().add(std::move(info), this); }
};
}  // namespace detail

}  // namespace imagenets

#define IMAGENETS_DETAIL_CAT2(a, b) a##b
#define IMAGENETS_DETAIL_CAT(a, b) IMAGENETS_DETAIL_CAT2(a, b)

// Registers Class (default-constructible, derived from imagenets::Block) under TypeName, and
// exports it as the nodelet plug-in `imagenets::BlockNodelet<Class>` (the plug-in XML, generated
// by `imagenets blocks --plugin-xml`, names it TypeName). Use it at namespace scope, spelling
// Class the same way everywhere (the plug-in type is the spelling, character for character).
#define IMAGENETS_REGISTER_BLOCK(Class, TypeName, Category, Doc)                                \
  static ::imagenets::detail::BlockRegistration IMAGENETS_DETAIL_CAT(imagenets_block_reg_,      \
                                                                     __LINE__)(                 \
      ::imagenets::BlockInfo{TypeName, #Class, Category, Doc,                                    \
                             []() -> std::unique_ptr<::imagenets::Block> {                       \
                               return std::make_unique<Class>();                                 \
                             },                                                                  \
                             &typeid(Class), std::string()});                                    \
  PLUGINLIB_EXPORT_CLASS(imagenets::BlockNodelet<Class>, nodelet::Nodelet)
