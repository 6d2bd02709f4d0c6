// The executor built from the edited document: a new document is diffed into it (a structural
// change builds the net anew; a property change goes to the running executor, so only that block
// and its downstream run again), it runs on request and its watched ports go to the tabs.
// Run events go to every tab as they happen.
#pragma once

#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "designer_output.h"
#include "imagenets/executor.h"
#include "net_document.h"
#include "port_watches.h"

namespace imagenets {
namespace designer {

class LiveNet {
 public:
  LiveNet(DesignerOutput& out, int threads);
  ~LiveNet();

  // Builds the executor of `doc` anew; throws NetError (nothing changed) when the engine refuses it.
  void rebuild(const NetDocument& doc);
  // From the executor of `previous` to one of `next`; throws NetError (nothing changed) when the
  // engine refuses it.
  void install(const NetDocument& previous, const NetDocument& next);

  enum class RunKind { OutOfDate, All, FromBlock, BlockOnly };
  struct Run {
    RunReport report;
    std::vector<std::string> cached;  // blocks served from their cache
  };
  // `block` (FromBlock, BlockOnly) must be in the net: RequestError otherwise.
  Run run(RunKind kind, const std::string& block = "");
  long runs() const { return runs_; }
  void cancel();  // any thread

  const Executor& executor() const { return *executor_; }
  const Net& net() const { return executor_->net(); }
  // The block of the built net; RequestError if there is none of that name.
  const Block& block(const std::string& name) const;

  // Watches `ports` (block.port of this net: NetError otherwise) for `client`.
  void watch(int client, const std::string& mode, const std::set<std::string>& ports);
  void disconnected(int client) { watches_.forget(client); }
  // Changed watched values to one tab, or every tab; `header` goes into each frame.
  void sendPortData(int client, const nlohmann::json& header);
  void sendPortData(const nlohmann::json& header);

 private:
  // The values of `names` for block `b` of `doc` (a setting's value, else the default); NetError
  // naming the block and property.
  PropertyValues valuesOf(const NetDocument& doc, const BlockSpec& b, const std::set<std::string>& names) const;

  DesignerOutput& out_;
  int threads_;
  std::unique_ptr<Executor> executor_;
  mutable std::mutex executor_mutex_;  // guards executor_ swaps against cancel() from other threads
  long runs_ = 0;
  std::mutex cached_mutex_;
  std::vector<std::string> cached_;  // blocks served from cache in the run in progress
  PortWatches watches_;
};

}  // namespace designer
}  // namespace imagenets
