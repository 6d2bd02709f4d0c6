// `imagenets blocks`: the paper's block browser. Blocks sorted alphabetically within categories,
// filterable by category and by input / output data type.
#include <iostream>

#include "imagenets/tool/command.h"
#include "imagenets/nodelet_plugins.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace tool {
namespace {

bool hasPortOfType(const std::vector<PortSpec>& ports, const std::string& type) {
  for (const auto& p : ports) {
    if (p.type->name == type) return true;
  }
  return false;
}

int run(const Args& args) {
  std::string category, input_type, output_type, library;
  bool plugin_xml = false;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--category") category = flagValue(args, i);
    else if (args[i] == "--input-type") input_type = flagValue(args, i);
    else if (args[i] == "--output-type") output_type = flagValue(args, i);
    else if (args[i] == "--plugin-xml") plugin_xml = true;
    else if (args[i] == "--library") library = flagValue(args, i);
    else throw unknownArgument(args[i]);
  }
  BlockRegistry::instance().loadLibraries();
  if (plugin_xml) {
    std::cout << nodeletPluginXml(library);
    return 0;
  }
  std::string current;
  size_t shown = 0;
  for (const BlockInfo* info : BlockRegistry::instance().all()) {
    if (!category.empty() && info->category != category) continue;
    auto block = BlockRegistry::instance().create(info->type);
    if (!input_type.empty() && !hasPortOfType(block->inputs(), input_type)) continue;
    if (!output_type.empty() && !hasPortOfType(block->outputs(), output_type)) continue;
    if (info->category != current) {
      current = info->category;
      std::cout << (shown ? "\n" : "") << "[" << current << "]\n";
    }
    ++shown;
    std::cout << "  " << info->type << " - " << info->doc << "\n";
    for (const auto& p : block->inputs()) {
      std::cout << "      in  " << p.name << " [" << p.type->name << "]" << (p.optional ? " (optional)" : "")
                << "  " << p.doc << "\n";
    }
    for (const auto& p : block->outputs()) {
      std::cout << "      out " << p.name << " [" << p.type->name << "]  " << p.doc << "\n";
    }
    for (const auto& s : block->propertySpecs()) {
      std::cout << "      property " << s.name() << " (" << kindName(s.kind()) << ") = " << toString(s.defaultValue());
      if (s.min() || s.max()) {
        std::cout << " [" << (s.min() ? toString(*s.min()) : "-inf") << ", " << (s.max() ? toString(*s.max()) : "inf")
                  << "]";
      }
      if (!s.allowedChoices().empty()) {
        std::cout << " {";
        for (size_t i = 0; i < s.allowedChoices().size(); ++i) std::cout << (i ? ", " : "") << s.allowedChoices()[i];
        std::cout << "}";
      }
      std::cout << "  " << s.doc() << "\n";
    }
  }
  if (shown == 0) {
    std::cerr << "no block matches\n";
    return 1;
  }
  return 0;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(blocks, "blocks", "blocks [--category C] [--input-type T] [--output-type T] [--plugin-xml [--library NAME]]",
                       "list the registered blocks with ports, properties and docs", run);

}  // namespace tool
}  // namespace imagenets
