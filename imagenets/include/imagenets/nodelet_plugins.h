// The nodelet plug-ins of registered blocks: which shared library exports which block as a nodelet
// (IMAGENETS_EXPORT_BLOCK_NODELET, register_block.h), and the plug-in description pluginlib reads.
#pragma once

#include <string>
#include <typeinfo>

namespace imagenets {

// The nodelet plug-in description (a package's nodelet_plugins.xml): one <library> per shared
// library of this process that exports block nodelets (programs and test executables are left
// out), one <class> per block, named by its type; only library `library` (e.g. "imagenets_blocks"
// for libimagenets_blocks.so) unless empty. Printed by `imagenets blocks --plugin-xml [--library
// NAME]`; each package's test checks its committed file.
std::string nodeletPluginXml(const std::string& library = "");

namespace detail {
struct NodeletExport {
  // `plugin_type`: the nodelet class as PLUGINLIB_EXPORT_CLASS spells it.
  NodeletExport(const std::type_info& block, const char* plugin_type);
};
}  // namespace detail

}  // namespace imagenets
