// The output ports each tab watches, per mode (preview, full), and what each tab was sent last:
// a value goes to a tab once, encoded once for all tabs.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include <boost/shared_ptr.hpp>
#include <nlohmann/json.hpp>

#include "designer_output.h"
#include "imagenets/executor.h"

namespace imagenets {
namespace designer {

class PortWatches {
 public:
  // Replaces what `client` watches in `mode`; ports no longer watched are forgotten, so watching
  // one again sends its value again.
  void watch(int client, const std::string& mode, std::set<std::string> ports);
  void forget(int client);
  // A new executor: its values are encoded anew even where they share data with the old one.
  void newExecutor() { encoded_.clear(); }
  // Every watched value that changed since it was sent, to its tab (one tab, or every tab);
  // `header` goes into each frame.
  void send(int client, const Executor& executor, DesignerOutput& out, const nlohmann::json& header);
  void send(const Executor& executor, DesignerOutput& out, const nlohmann::json& header);

 private:
  std::map<int, std::map<std::string, std::set<std::string>>> watches_;
  std::map<std::pair<int, std::string>, boost::shared_ptr<const void>> sent_;
  std::map<std::string, std::pair<boost::shared_ptr<const void>, std::shared_ptr<const std::string>>> encoded_;
};

}  // namespace designer
}  // namespace imagenets
