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

void declare(Flags& f) {
  f.add()("category", po::value<std::string>()->default_value(""), "only the blocks of this category")
      ("input-type", po::value<std::string>()->default_value(""), "only blocks with an input of this type")
      ("output-type", po::value<std::string>()->default_value(""), "only blocks with an output of this type")
      ("plugin-xml", po::bool_switch(), "print the nodelet plug-in XML instead")
      ("library", po::value<std::string>()->default_value(""), "with --plugin-xml: only the blocks of this library");
}

int run(const Options& o) {
  const std::string category = o["category"].as<std::string>();
  const std::string input_type = o["input-type"].as<std::string>();
  const std::string output_type = o["output-type"].as<std::string>();
  BlockRegistry::instance().loadLibraries();
  if (o["plugin-xml"].as<bool>()) {
    std::cout << nodeletPluginXml(o["library"].as<std::string>());
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
                       "list the registered blocks with ports, properties and docs", declare, run);

}  // namespace tool
}  // namespace imagenets
