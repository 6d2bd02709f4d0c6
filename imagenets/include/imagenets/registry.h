// The block registry: every block type by name ("imagenets/Threshold"), with its category and
// one-line doc, found by nets, the `imagenets blocks` browser, the Designer and the nodelet host.
// A block library registers each block with IMAGENETS_REGISTER_BLOCK (register_block.h, which
// also exports it as a nodelet); code without nodelets uses IMAGENETS_REGISTER_BLOCK_TYPE here.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

#include "imagenets/block.h"

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
  // A type's former name, which nets and launch files written before a rename still use.
  void addFormerName(const std::string& former, const std::string& type);
  // Finds a type by its name or a former name.
  const BlockInfo* find(const std::string& type) const;
  const BlockInfo* findByTypeId(const std::type_info& cpp_type) const;
  std::vector<const BlockInfo*> all() const;  // sorted by category, then type
  // Creates a block with its info set; throws std::runtime_error for an unknown type.
  std::unique_ptr<Block> create(const std::string& type) const;
  // A type the registry does not know may live in a library not loaded yet (a nodelet manager
  // loads only the library of the nodelet it was asked for): `loader` loads more block libraries.
  // Set by the nodelet layer; findOrLoad() calls it once, on the first unknown type, and
  // loadLibraries() (for whoever lists every block: the tool, the Designer) at once.
  void setLibraryLoader(std::function<void()> loader);
  const BlockInfo* findOrLoad(const std::string& type);
  void loadLibraries();
  // Known types closest to an unknown name (edit distance), best first.
  std::vector<std::string> suggest(const std::string& type, size_t max = 3) const;
  // Type names claimed by two different classes (the first one wins); should be empty.
  const std::vector<std::string>& conflicts() const { return conflicts_; }
  // former name -> type
  const std::map<std::string, std::string>& formerNames() const { return former_names_; }

 private:
  std::vector<std::unique_ptr<BlockInfo>> infos_;
  std::vector<std::string> conflicts_;
  std::map<std::string, std::string> former_names_;
  std::function<void()> loader_;
  bool loaded_ = false;
};

namespace detail {
struct BlockRegistration {
  BlockRegistration(BlockInfo info) { BlockRegistry::instance().add(std::move(info), this); }
};
struct FormerNameRegistration {
  FormerNameRegistration(const char* former, const char* type) { BlockRegistry::instance().addFormerName(former, type); }
};
}  // namespace detail

}  // namespace imagenets

#define IMAGENETS_DETAIL_CAT2(a, b) a##b
#define IMAGENETS_DETAIL_CAT(a, b) IMAGENETS_DETAIL_CAT2(a, b)

// Registers Class (default-constructible, derived from imagenets::Block) under TypeName. Use it at
// namespace scope.
#define IMAGENETS_REGISTER_BLOCK_TYPE(Class, TypeName, Category, Doc)                           \
  static ::imagenets::detail::BlockRegistration IMAGENETS_DETAIL_CAT(imagenets_block_reg_,      \
                                                                     __LINE__)(                 \
      ::imagenets::BlockInfo{TypeName, #Class, Category, Doc,                                    \
                             []() -> std::unique_ptr<::imagenets::Block> {                       \
                               return std::make_unique<Class>();                                 \
                             },                                                                  \
                             &typeid(Class), std::string()})

// Keeps FormerName loading as TypeName (in nets, and as a nodelet in launch files) after a rename.
#define IMAGENETS_REGISTER_BLOCK_FORMER_NAME(FormerName, TypeName)                                           \
  static ::imagenets::detail::FormerNameRegistration IMAGENETS_DETAIL_CAT(imagenets_block_former_, __LINE__)( \
      FormerName, TypeName)
