// The Designer's edits of a net: each takes a document and returns the edited one, leaving the
// input alone, so that undo keeps the old one and the edits can be tested without an executor.
// An edit naming what does not exist throws RequestError; whether the engine accepts the result
// (types of linked ports, a block's properties) is for Net::build to say when it is installed.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "net_document.h"
#include "request_error.h"

namespace imagenets {
namespace designer {
namespace edits {

using Position = std::array<double, 2>;

// "imagenets/ImageFileSource" -> "image_file_source"
std::string nameFromType(const std::string& type);
// `wanted`, else wanted_2, wanted_3, ...: a name neither in `doc` nor in `taken`.
std::string freeName(const NetDocument& doc, const std::string& wanted, const std::set<std::string>& taken = {});
// "block.port" -> (block, port), as the net file writes it; `what` names the field in errors.
std::pair<std::string, std::string> splitEndpoint(const std::string& text, const std::string& what);
const BlockSpec& block(const NetDocument& doc, const std::string& name);

NetDocument addBlock(const NetDocument& doc, BlockSpec block, const std::optional<Position>& position);
// Also removes their links, their positions, the feedback they score and initial values read
// from their ports.
NetDocument removeBlocks(const NetDocument& doc, const std::set<std::string>& names);
NetDocument moveBlocks(const NetDocument& doc, const std::map<std::string, Position>& positions);
NetDocument addLink(const NetDocument& doc, const std::string& from, const std::string& to);
NetDocument removeLink(const NetDocument& doc, const std::string& from, const std::string& to);
// No text: the property goes back to its default.
NetDocument setProperty(const NetDocument& doc, const std::string& block, const std::string& property,
                        const std::optional<std::string>& text);
NetDocument setFeedback(const NetDocument& doc, const std::string& block, std::optional<FeedbackSpec> feedback);
// Links, feedback references and the position follow the new name.
NetDocument renameBlock(const NetDocument& doc, const std::string& from, const std::string& to);

struct PastedBlock {
  BlockSpec spec;  // named as copied
  std::optional<Position> position;
};
struct Pasted {
  NetDocument doc;
  std::map<std::string, std::string> names;  // as copied -> as pasted (unique in the net)
};
// Blocks copied elsewhere, with the links (block.port -> block.port) between them or to blocks
// of the net; links and feedback references follow the blocks' new names.
Pasted paste(const NetDocument& doc, const std::vector<PastedBlock>& blocks,
             const std::vector<std::pair<std::string, std::string>>& links);
// The net written as text (throws NetError naming the line); positions of blocks that stay and
// are not in the text are kept.
NetDocument setText(const NetDocument& doc, const std::string& text);

}  // namespace edits
}  // namespace designer
}  // namespace imagenets
