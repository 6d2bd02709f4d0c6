// The edits every tool makes to a net before building it (the Designer, `imagenets run --set`, a
// node swapping a sub-net): one definition of finding a block, setting a property, removing a block.
#include <algorithm>

#include "imagenets/net.h"

namespace imagenets {

const PropertySetting* BlockSpec::findSetting(const std::string& property) const {
  for (const PropertySetting& p : properties) {
    if (p.name == property) return &p;
  }
  return nullptr;
}

void BlockSpec::setProperty(const std::string& property, const std::string& text) {
  for (PropertySetting& p : properties) {
    if (p.name != property) continue;
    p.text = text;
    return;
  }
  properties.push_back(PropertySetting{property, text, loc});
}

bool BlockSpec::removeProperty(const std::string& property) {
  const auto it = std::find_if(properties.begin(), properties.end(),
                               [&](const PropertySetting& p) { return p.name == property; });
  if (it == properties.end()) return false;
  properties.erase(it);
  return true;
}

BlockSpec* NetSpec::findBlock(const std::string& name) {
  for (BlockSpec& b : blocks) {
    if (b.name == name) return &b;
  }
  return nullptr;
}

const BlockSpec* NetSpec::findBlock(const std::string& name) const {
  return const_cast<NetSpec*>(this)->findBlock(name);
}

BlockSpec& NetSpec::block(const std::string& name) {
  BlockSpec* b = findBlock(name);
  if (!b) throw NetError({origin + ": no block named '" + name + "'"});
  return *b;
}

const BlockSpec& NetSpec::block(const std::string& name) const { return const_cast<NetSpec*>(this)->block(name); }

bool NetSpec::removeBlock(const std::string& name) {
  const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const BlockSpec& b) { return b.name == name; });
  if (it == blocks.end()) return false;
  blocks.erase(it);
  links.erase(std::remove_if(links.begin(), links.end(),
                             [&](const LinkSpec& l) { return l.from_block == name || l.to_block == name; }),
              links.end());
  for (BlockSpec& b : blocks) {
    if (!b.feedback) continue;
    if (b.feedback->score_block == name) {
      b.feedback.reset();  // a feedback without its score means nothing
      continue;
    }
    auto& initial = b.feedback->initial;
    initial.erase(std::remove_if(initial.begin(), initial.end(), [&](const FeedbackInitial& i) { return i.block == name; }),
                  initial.end());
  }
  return true;
}

}  // namespace imagenets
