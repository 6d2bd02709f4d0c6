#include "net_document.h"

#include <boost/filesystem.hpp>
#include <yaml-cpp/yaml.h>

#include "imagenets/net_writer.h"
#include "imagenets/registry.h"

namespace imagenets {
namespace designer {

NetDocument NetDocument::empty(const std::string& origin, const std::string& base_dir) {
  NetDocument doc;
  doc.spec.origin = origin;
  doc.spec.base_dir = base_dir;
  return doc;
}

NetDocument NetDocument::fromText(const std::string& text, const std::string& origin, const std::string& base_dir) {
  NetDocument doc;
  doc.spec = parseNetText(text, origin, base_dir);
  doc.source_text_ = text;
  doc.source_written_ = writeNetText(doc.spec);
  // The engine ignores `designer:`; a malformed one loses the positions, not the net.
  try {
    const YAML::Node positions = YAML::Load(text)["designer"]["positions"];
    if (positions && positions.IsMap()) {
      for (const auto& kv : positions) {
        if (kv.second.IsSequence() && kv.second.size() == 2) {
          doc.positions[kv.first.Scalar()] = {kv.second[0].as<double>(), kv.second[1].as<double>()};
        }
      }
    }
  } catch (const YAML::Exception&) {
  }
  return doc;
}

std::string NetDocument::text() const {
  const std::string written = writeNetText(spec, source_text_);
  const bool unchanged = !source_text_.empty() && writeNetText(spec) == source_written_;
  std::string out = unchanged ? source_text_ : written;
  Positions kept;
  for (const auto& kv : positions) {
    if (spec.findBlock(kv.first)) kept.insert(kv);
  }
  std::string body;
  if (!kept.empty()) {
    YAML::Emitter e;
    e << YAML::Flow << YAML::BeginMap;
    for (const auto& kv : kept) {
      e << YAML::Key << kv.first << YAML::Value << YAML::Flow << YAML::BeginSeq << formatNumber(kv.second[0])
        << formatNumber(kv.second[1]) << YAML::EndSeq;
    }
    e << YAML::EndMap;
    body = std::string("positions: ") + e.c_str();
  }
  // An unchanged net without positions keeps its text exactly, section and all.
  if (unchanged && kept.empty()) return out;
  return setTopLevelSection(out, "designer", body);
}

bool NetDocument::sameNet(const NetDocument& other) const { return writeNetText(spec) == writeNetText(other.spec); }

void NetDocument::moveTo(const std::string& origin, const std::string& base_dir) {
  namespace fs = boost::filesystem;
  if (fs::path(base_dir).lexically_normal() != fs::path(spec.base_dir).lexically_normal()) {
    for (BlockSpec& b : spec.blocks) {
      const BlockInfo* info = BlockRegistry::instance().find(b.type);
      if (!info) continue;
      const auto block = info->create();
      for (PropertySetting& p : b.properties) {
        const PropertySpec* ps = block->findProperty(p.name);
        if (!ps || !ps->isPath()) continue;
        try {
          const std::string value = std::get<std::string>(ps->parse(p.text));
          if (value.empty() || value[0] == '/' || value[0] == '$') continue;
          const fs::path absolute = fs::path(resolvePath(value, spec.base_dir));
          p.text = absolute.lexically_relative(fs::path(base_dir)).string();
        } catch (const std::exception&) {
        }
      }
    }
  }
  spec.origin = origin;
  spec.base_dir = base_dir;
}

void NetDocument::rebase(const std::string& text) {
  source_text_ = text;
  source_written_ = writeNetText(spec);
}

}  // namespace designer
}  // namespace imagenets
