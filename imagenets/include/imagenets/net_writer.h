// Writes a NetSpec back as net-file text that parseNetText / `imagenets validate` accept, and edits
// top-level sections of a net file's text while leaving every other line (comments, order,
// formatting) as it was. Used by any program that edits nets (the Designer saves with it).
//
//   std::string text = imagenets::writeNetText(spec, previous_text);  // docs kept from previous_text
//   text = imagenets::setTopLevelSection(text, "designer", "positions: {gray: [120, 40]}");
#pragma once

#include <string>

#include "imagenets/net.h"

namespace imagenets {

// The net as YAML: blocks in spec order with type, properties (their text as written), feedback;
// links as 'a.port -> b.port'. The net's and each block's `doc` are taken from previous_text (a
// net file's text; ignored when empty or malformed), so re-writing a documented net keeps them.
std::string writeNetText(const NetSpec& spec, const std::string& previous_text = "");

// One block's feedback as a YAML flow map with the keys of the net file: from/to/step when the
// candidates are evenly spaced, else values.
std::string writeFeedbackText(const FeedbackSpec& feedback);

// Replaces the top-level section `key:` of a net file's text (up to the next line that starts in
// column 0) with `key:` followed by `body` indented by two spaces, or appends it. An empty body
// removes the section. Every other line stays as it was.
std::string setTopLevelSection(const std::string& text, const std::string& key, const std::string& body);

// The shortest decimal text that reads back as exactly `value` ("0.1", "40", "1e-05").
std::string formatNumber(double value);

}  // namespace imagenets
