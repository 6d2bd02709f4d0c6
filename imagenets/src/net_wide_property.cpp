#include "imagenets/net_wide_property.h"

#include "imagenets/executor.h"
#include "imagenets/inner_net.h"

namespace imagenets {
namespace {

// True when it set any block of `exec`'s tree.
bool setIn(Executor& exec, const std::string& prefix, const std::string& property, const std::string& text,
           const std::function<bool(const PropertySpec&)>& accept, std::vector<std::string>& set) {
  const size_t before = set.size();
  for (const auto& node : exec.net().nodes()) {
    const PropertySpec* spec = node.block->findProperty(property);
    if (spec && (!accept || accept(*spec))) {
      exec.setPropertyText(node.name, property, text);
      set.push_back(prefix + node.name);
    }
    // A sub-net's blocks are set in its own executor (built when the outer net was).
    auto* inner = dynamic_cast<InnerNet*>(node.block.get());
    if (!inner) continue;
    bool changed = false;
    for (const InnerExecutorRef& net : inner->innerExecutors()) {
      const std::string path = prefix + node.name + "/" + (net.path.empty() ? "" : net.path + "/");
      changed = setIn(*net.executor, path, property, text, accept, set) || changed;
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
  setIn(exec, "", property, text, accept, set);
  return set;
}

}  // namespace imagenets
