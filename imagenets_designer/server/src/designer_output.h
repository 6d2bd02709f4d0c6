// Where the Designer's messages go: the server's connections (tests use their own).
#pragma once

#include <memory>
#include <string>

namespace imagenets {
namespace designer {

class DesignerOutput {
 public:
  virtual ~DesignerOutput() = default;
  virtual void send(int client, const std::string& text) = 0;  // one tab
  virtual void broadcast(const std::string& text) = 0;        // every tab
  // Port data for one tab; `slot` ("block.port|mode") names the value, so a newer frame for the
  // same slot replaces one not sent yet.
  virtual void sendPortData(int client, const std::string& slot, std::shared_ptr<const std::string> frame) = 0;
};

}  // namespace designer
}  // namespace imagenets
