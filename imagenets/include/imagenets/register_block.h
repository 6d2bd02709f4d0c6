// IMAGENETS_REGISTER_BLOCK: the one line a block library's .cpp adds. It registers the block type
// (registry.h: found by nets, the `imagenets blocks` browser, the Designer) and exports it as the
// nodelet plug-in `imagenets::BlockNodelet<Class>` of the nodelet host (block_nodelet.h), named
// TypeName in the plug-in XML (`imagenets blocks --plugin-xml`). Use it at namespace scope,
// spelling Class the same way everywhere (the plug-in type is the spelling, character for character).
//
// This header belongs to the nodelet layer (library imagenets_nodelet). Code that needs no
// nodelets (the engine, its tests, a program embedding nets) registers with
// IMAGENETS_REGISTER_BLOCK_TYPE from registry.h.
#pragma once

#include <pluginlib/class_list_macros.hpp>

#include "imagenets/block_nodelet.h"
#include "imagenets/nodelet_plugins.h"
#include "imagenets/registry.h"

// Exports an already registered block type as its nodelet.
#define IMAGENETS_EXPORT_BLOCK_NODELET(Class)                                                          \
  static ::imagenets::detail::NodeletExport IMAGENETS_DETAIL_CAT(imagenets_nodelet_export_, __LINE__)( \
      typeid(Class), "imagenets::BlockNodelet<" #Class ">");                                           \
  PLUGINLIB_EXPORT_CLASS(imagenets::BlockNodelet<Class>, nodelet::Nodelet)

#define IMAGENETS_REGISTER_BLOCK(Class, TypeName, Category, Doc) \
  IMAGENETS_REGISTER_BLOCK_TYPE(Class, TypeName, Category, Doc); \
  IMAGENETS_EXPORT_BLOCK_NODELET(Class)
