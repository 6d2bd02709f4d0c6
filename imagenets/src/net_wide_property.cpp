#include "imagenets/net_wide_property.h"

#include "imagenets/executor.h"
#include "imagenets/inner_net.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace {

// Whether a block of the tree takes the value (`where`: its net and name, for messages).
using Select = std::function<bool(const Block& block, const PropertySpec& spec, const std::string& where)>;

// True when it set any block of `exec`'s tree.
bool setIn(Executor& exec, const std::string& prefix, const std::string& property, const std::string& text,
           const Select& select, std::vector<std::string>& set) {
  const size_t before = set.size();
  for (const auto& node : exec.net().nodes()) {
    const PropertySpec* spec = node.block->findProperty(property);
    if (spec && select(*node.block, *spec, exec.net().origin() + ": block '" + node.name + "'")) {
      exec.setPropertyText(node.name, property, text);
      set.push_back(prefix + node.name);
    }
    // A sub-net's blocks are set in its own executor (built when the outer net was).
    auto* inner = dynamic_cast<InnerNet*>(node.block.get());
    if (!inner) continue;
    bool changed = false;
    for (const InnerExecutorRef& net : inner->innerExecutors()) {
      const std::string path = prefix + node.name + "/" + (net.path.empty() ? "" : net.path + "/");
      changed = setIn(*net.executor, path, property, text, select, set) || changed;
    }
    // The outer executor caches the sub-net block's outputs: the next run re-runs the changed sub-net.
    if (changed) exec.markOutOfDate(node.name);
  }
  return set.size() > before;
}

}  // namespace

std::vector<std::string> setPropertyInNetTree(Executor& exec, const std::string& property, const std::string& text,
                                              const std::function<bool(const PropertySpec&)>& accept) {
  std::vector<std::string> set;
  setIn(exec, "", property, text, [&](const Block&, const PropertySpec& spec, const std::string&) { return !accept || accept(spec); },
        set);
  return set;
}

std::vector<std::string> replacePropertyValueInNetTree(Executor& exec, const std::string& block_type,
                                                       const std::string& property, const std::string& from,
                                                       const std::string& to) {
  std::vector<std::string> set;
  const Select holds_from = [&](const Block& block, const PropertySpec& spec, const std::string& where) {
    if (!block.info() || block.info()->type != block_type) return false;
    PropertyValue old;
    try {
      old = spec.parse(from);  // relative paths: the working directory, as setPropertyText takes `to`
    } catch (const PropertyError& e) {
      throw NetError({where + ": property '" + property + "': the value to replace: " + e.what()});
    }
    return block.propertyValue(property) == old;
  };
  setIn(exec, "", property, to, holds_from, set);
  return set;
}

}  // namespace imagenets
