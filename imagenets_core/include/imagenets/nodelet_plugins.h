// The nodelet plug-ins of registered blocks: which shared library exports which block as a nodelet
// (IMAGENETS_EXPORT_BLOCK_NODELET, register_block.h), and the plug-in description pluginlib reads.
#pragma once

#include <string>
#include <typeinfo>

namespace imagenets {

// The nodelet plug-in description (imagenets_plugins.xml): one <library> per shared library of
// this process that exports block nodelets (programs and test executables are left out), one
// <class> per block, named by its type. Printed by `imagenets blocks --plugin-xml`; a test checks
// the committed file.
std::string nodeletPluginXml();

namespace detail {
struct NodeletExport {
  // `plugin_type`: the nodelet class as PLUGINLIB_EXPORT_CLASS spells it.
  NodeletExport(const std::type_info& block, const char* plugin_type);
};
}  // namespace detail

}  // namespace imagenets
