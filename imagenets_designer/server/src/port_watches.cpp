#include "port_watches.h"

#include "port_data.h"

namespace imagenets {
namespace designer {

void PortWatches::watch(int client, const std::string& mode, std::set<std::string> ports) {
  for (const auto& old : watches_[client][mode]) {
    if (!ports.count(old)) sent_.erase({client, old + "|" + mode});
  }
  watches_[client][mode] = std::move(ports);
}

void PortWatches::forget(int client) {
  watches_.erase(client);
  for (auto it = sent_.begin(); it != sent_.end();) {
    it = it->first.first == client ? sent_.erase(it) : std::next(it);
  }
}

void PortWatches::send(const Executor& executor, DesignerOutput& out, const nlohmann::json& header) {
  for (const auto& kv : watches_) send(kv.first, executor, out, header);
}

void PortWatches::send(int client, const Executor& executor, DesignerOutput& out, const nlohmann::json& header) {
  auto w = watches_.find(client);
  if (w == watches_.end()) return;
  for (const auto& [mode, ports] : w->second) {
    for (const auto& port : ports) {
      Value value;
      try {
        value = executor.output(port);
      } catch (const NetError&) {
        continue;  // the block went away in an edit
      }
      const std::string slot = port + "|" + mode;
      auto sent = sent_.find({client, slot});
      if (sent != sent_.end() && sent->second == value.data) continue;
      auto& cached = encoded_[slot];
      if (!cached.second || cached.first != value.data) {
        nlohmann::json frame_header = header;
        frame_header["port"] = port;
        try {
          cached = {value.data, std::make_shared<const std::string>(encodePortFrame(value, mode, frame_header))};
        } catch (const std::exception& e) {
          frame_header["error"] = std::string("cannot show the value: ") + e.what();
          cached = {value.data, std::make_shared<const std::string>(encodePortFrame(Value(), mode, frame_header))};
        }
      }
      sent_[{client, slot}] = value.data;
      out.sendPortData(client, slot, cached.second);
    }
  }
}

}  // namespace designer
}  // namespace imagenets
