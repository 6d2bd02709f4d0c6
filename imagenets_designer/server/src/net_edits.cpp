#include "net_edits.h"

#include <algorithm>
#include <cctype>

namespace imagenets {
namespace designer {
namespace edits {

namespace {

BlockSpec& blockIn(NetDocument& doc, const std::string& name) {
  BlockSpec* b = doc.spec.findBlock(name);
  if (!b) throw RequestError("no block named '" + name + "'");
  return *b;
}

std::string endpoint(const std::string& block, const std::string& port) { return block + "." + port; }

}  // namespace

std::string nameFromType(const std::string& type) {
  const std::string base = type.substr(type.rfind('/') == std::string::npos ? 0 : type.rfind('/') + 1);
  std::string out;
  for (size_t i = 0; i < base.size(); ++i) {
    const char c = base[i];
    if (std::isupper(static_cast<unsigned char>(c))) {
      if (i > 0 && !std::isupper(static_cast<unsigned char>(base[i - 1]))) out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      out += c;
    }
  }
  return out.empty() ? "block" : out;
}

std::string freeName(const NetDocument& doc, const std::string& wanted, const std::set<std::string>& taken) {
  if (!doc.spec.findBlock(wanted) && !taken.count(wanted)) return wanted;
  for (int i = 2;; ++i) {
    const std::string name = wanted + "_" + std::to_string(i);
    if (!doc.spec.findBlock(name) && !taken.count(name)) return name;
  }
}

std::pair<std::string, std::string> splitEndpoint(const std::string& text, const std::string& what) {
  const auto dot = text.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == text.size()) {
    throw RequestError(what + " '" + text + "' is not of the form block.port");
  }
  return {text.substr(0, dot), text.substr(dot + 1)};
}

const BlockSpec& block(const NetDocument& doc, const std::string& name) {
  const BlockSpec* b = doc.spec.findBlock(name);
  if (!b) throw RequestError("no block named '" + name + "'");
  return *b;
}

NetDocument addBlock(const NetDocument& doc, BlockSpec block, const std::optional<Position>& position) {
  NetDocument next = doc;
  if (position) next.positions[block.name] = *position;
  next.spec.blocks.push_back(std::move(block));
  return next;
}

NetDocument removeBlocks(const NetDocument& doc, const std::set<std::string>& gone) {
  NetDocument next = doc;
  for (const auto& name : gone) blockIn(next, name);
  // Links, and a feedback scored by a removed block, go with it.
  for (const auto& name : gone) next.spec.removeBlock(name);
  for (const auto& name : gone) next.positions.erase(name);
  return next;
}

NetDocument moveBlocks(const NetDocument& doc, const std::map<std::string, Position>& positions) {
  NetDocument next = doc;
  for (const auto& [name, position] : positions) {
    blockIn(next, name);
    next.positions[name] = position;
  }
  return next;
}

NetDocument addLink(const NetDocument& doc, const std::string& from, const std::string& to) {
  LinkSpec l;
  std::tie(l.from_block, l.from_port) = splitEndpoint(from, "'from'");
  std::tie(l.to_block, l.to_port) = splitEndpoint(to, "'to'");
  l.loc = SourceLocation{doc.spec.origin, 0};
  NetDocument next = doc;
  next.spec.links.push_back(l);
  return next;
}

NetDocument removeLink(const NetDocument& doc, const std::string& from, const std::string& to) {
  NetDocument next = doc;
  auto& links = next.spec.links;
  auto it = std::find_if(links.begin(), links.end(), [&](const LinkSpec& l) {
    return endpoint(l.from_block, l.from_port) == from && endpoint(l.to_block, l.to_port) == to;
  });
  if (it == links.end()) throw RequestError("no link " + from + " -> " + to);
  links.erase(it);
  return next;
}

NetDocument setProperty(const NetDocument& doc, const std::string& name, const std::string& property,
                        const std::optional<std::string>& text) {
  NetDocument next = doc;
  BlockSpec& b = blockIn(next, name);
  if (text) b.setProperty(property, *text);
  else b.removeProperty(property);
  return next;
}

NetDocument setFeedback(const NetDocument& doc, const std::string& name, std::optional<FeedbackSpec> feedback) {
  NetDocument next = doc;
  blockIn(next, name).feedback = std::move(feedback);
  return next;
}

NetDocument renameBlock(const NetDocument& doc, const std::string& from, const std::string& to) {
  NetDocument next = doc;
  blockIn(next, from).name = to;
  if (from != to && doc.spec.findBlock(to)) throw RequestError("a block named '" + to + "' exists already");
  for (auto& l : next.spec.links) {
    if (l.from_block == from) l.from_block = to;
    if (l.to_block == from) l.to_block = to;
  }
  for (auto& b : next.spec.blocks) {
    if (!b.feedback) continue;
    if (b.feedback->score_block == from) b.feedback->score_block = to;
    for (auto& initial : b.feedback->initial) {
      if (initial.block == from) initial.block = to;
    }
  }
  auto pos = next.positions.find(from);
  if (pos != next.positions.end()) {
    const auto p = pos->second;
    next.positions.erase(pos);
    next.positions[to] = p;
  }
  return next;
}

Pasted paste(const NetDocument& doc, const std::vector<PastedBlock>& blocks,
             const std::vector<std::pair<std::string, std::string>>& links) {
  Pasted out{doc, {}};
  std::set<std::string> taken;
  for (const auto& item : blocks) {
    const std::string name = freeName(doc, item.spec.name, taken);
    taken.insert(name);
    out.names[item.spec.name] = name;
  }
  auto renamed = [&](const std::string& name) {
    auto it = out.names.find(name);
    return it == out.names.end() ? name : it->second;
  };
  for (const auto& item : blocks) {
    BlockSpec b = item.spec;
    b.name = renamed(b.name);
    b.loc = SourceLocation{doc.spec.origin, 0};
    for (auto& p : b.properties) p.loc = b.loc;
    if (item.position) out.doc.positions[b.name] = *item.position;
    if (b.feedback) {
      b.feedback->score_block = renamed(b.feedback->score_block);
      for (auto& initial : b.feedback->initial) {
        if (initial.fromPort()) initial.block = renamed(initial.block);
      }
    }
    out.doc.spec.blocks.push_back(std::move(b));
  }
  for (const auto& [from, to] : links) {
    LinkSpec l;
    std::tie(l.from_block, l.from_port) = splitEndpoint(from, "'from'");
    std::tie(l.to_block, l.to_port) = splitEndpoint(to, "'to'");
    l.from_block = renamed(l.from_block);
    l.to_block = renamed(l.to_block);
    l.loc = SourceLocation{doc.spec.origin, 0};
    out.doc.spec.links.push_back(l);
  }
  return out;
}

NetDocument setText(const NetDocument& doc, const std::string& text) {
  NetDocument next = NetDocument::fromText(text, doc.spec.origin, doc.spec.base_dir);
  for (const auto& kv : doc.positions) {
    if (next.spec.findBlock(kv.first) && !next.positions.count(kv.first)) next.positions.insert(kv);
  }
  return next;
}

}  // namespace edits
}  // namespace designer
}  // namespace imagenets
