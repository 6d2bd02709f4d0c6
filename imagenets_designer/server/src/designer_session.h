// The Designer's state and requests (designer/PROTOCOL.md), apart from any network code: the net
// being edited (NetDocument), the executor built from it, undo/redo, files, runs, watched ports.
// The server calls handle() for one request at a time (from its worker thread) and cancel() from
// any thread; the session answers through an Output.
//
// Structural edits rebuild the executor (Net::build validates them: a refused edit changes
// nothing and returns the engine's message); property changes go to the running executor, so
// only that block and its downstream run again.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "allowed_roots.h"
#include "imagenets/executor.h"
#include "net_document.h"

namespace imagenets {
namespace designer {

// A request the session cannot serve: the text names what is wrong and where.
struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class DesignerSession {
 public:
  class Output {
   public:
    virtual ~Output() = default;
    virtual void send(int client, const std::string& text) = 0;  // one tab
    virtual void broadcast(const std::string& text) = 0;        // every tab
    // Port data for one tab; `slot` ("block.port|mode") names the value, so a newer frame for the
    // same slot replaces one not sent yet.
    virtual void sendPortData(int client, const std::string& slot, std::shared_ptr<const std::string> frame) = 0;
  };

  struct Options {
    std::vector<std::string> roots;  // besides the net's folder and the package's config/
    int threads = 0;                 // executor threads (0 = cores)
  };

  DesignerSession(Output& output, Options options);
  ~DesignerSession();

  // Loads the net given on the command line (a file that does not exist yet: a new net saved
  // under that name). A net that does not load leaves an empty net with the errors in the net
  // state (and returns false).
  bool openStartupNet(const std::string& path);

  // One request (a JSON object with "op" and "id"); the reply goes to `client`.
  void handle(int client, const nlohmann::json& request);
  // Stops the run in progress, if any (any thread).
  void cancel();
  void disconnected(int client);

  const AllowedRoots& roots() const { return roots_; }
  std::string fileName() const { return file_; }
  // The current net state (the `net` push).
  nlohmann::json netState() const;

 private:
  struct Snapshot {
    NetDocument doc;
    std::string merge;  // edits with the same non-empty key in a row make one undo step
  };
  using Handler = nlohmann::json (DesignerSession::*)(int client, const nlohmann::json& request);
  static const std::map<std::string, Handler>& handlers();

  // Edits.
  nlohmann::json opHello(int, const nlohmann::json&);
  nlohmann::json opRegistry(int, const nlohmann::json&);
  nlohmann::json opAddBlock(int, const nlohmann::json&);
  nlohmann::json opRemoveBlocks(int, const nlohmann::json&);
  nlohmann::json opMoveBlocks(int, const nlohmann::json&);
  nlohmann::json opAddLink(int, const nlohmann::json&);
  nlohmann::json opRemoveLink(int, const nlohmann::json&);
  nlohmann::json opSetProperty(int, const nlohmann::json&);
  nlohmann::json opSetFeedback(int, const nlohmann::json&);
  nlohmann::json opRenameBlock(int, const nlohmann::json&);
  nlohmann::json opPaste(int, const nlohmann::json&);
  nlohmann::json opSetYaml(int, const nlohmann::json&);
  nlohmann::json opUndo(int, const nlohmann::json&);
  nlohmann::json opRedo(int, const nlohmann::json&);
  nlohmann::json opAutoRun(int, const nlohmann::json&);
  // Runs.
  nlohmann::json opRun(int, const nlohmann::json&);
  nlohmann::json opRunAll(int, const nlohmann::json&);
  nlohmann::json opRunBlock(int, const nlohmann::json&);
  nlohmann::json opRunBlockOnly(int, const nlohmann::json&);
  nlohmann::json opCancel(int, const nlohmann::json&);
  // Files and export.
  nlohmann::json opOpen(int, const nlohmann::json&);
  nlohmann::json opSave(int, const nlohmann::json&);
  nlohmann::json opListFiles(int, const nlohmann::json&);
  nlohmann::json opExportLaunch(int, const nlohmann::json&);
  nlohmann::json opExportGraph(int, const nlohmann::json&);
  nlohmann::json opSubnet(int, const nlohmann::json&);
  nlohmann::json opSubnetOpen(int, const nlohmann::json&);
  nlohmann::json opWatch(int, const nlohmann::json&);

  // Makes `next` the edited net: rebuilds the executor when the net's structure changed, else
  // passes the changed properties to the executor (its cache stays valid). Throws NetError
  // (nothing changed) when the engine refuses it.
  void install(NetDocument next);
  // install() as one undo step, and the new state to every tab. Consecutive edits with the same
  // non-empty `merge` key (one property dragged along a slider) are one step.
  // Undo (from = undo_, to = redo_) or redo: the top state of `from` becomes the net.
  nlohmann::json step(std::vector<Snapshot>& from, std::vector<Snapshot>& to, const std::string& what);
  // `notify` false: the caller pushes the state later (after an automatic run).
  void apply(NetDocument next, const std::string& merge = "", bool notify = true);
  void rebuild(const NetDocument& doc);
  // Whether a property change from `previous` to `next` changes a block's configuration (its
  // sub-net, its ports): then the net is built anew instead of setting the property.
  bool configurationChanged(const NetDocument& previous, const NetDocument& next) const;
  void setExecutorProperty(const NetDocument& doc, const std::string& block, const std::string& property,
                           const std::string* text);
  void loadFile(const std::string& path);  // throws NetError; not an undo step
  nlohmann::json runReport(const RunReport& report) const;
  enum class RunKind { OutOfDate, All, FromBlock, BlockOnly };
  nlohmann::json runAndReport(RunKind kind, const std::string& block);
  void changed();          // revision++, push the net state
  void sendPortData();     // every watched port whose value changed, to its tab
  void sendPortData(int client);
  std::string baseDir() const;
  BlockSpec& block(NetDocument& doc, const std::string& name) const;

  Output& out_;
  Options options_;
  AllowedRoots roots_;
  NetDocument doc_;
  std::unique_ptr<Executor> executor_;
  mutable std::mutex executor_mutex_;  // guards executor_ swaps against cancel() from other threads
  int observer_ = -1;
  std::vector<Snapshot> undo_, redo_;
  std::string file_;  // "" for a net never saved
  std::string saved_text_;
  std::vector<std::string> errors_;
  long revision_ = 0;
  // Counts the nets opened (a file, a sub-net's file): what a page shows of one net (previews,
  // run results) must not carry over to another, even one with the same block names.
  long document_ = 0;
  long run_count_ = 0;
  std::mutex cached_mutex_;
  std::vector<std::string> cached_;  // blocks served from cache in the run in progress
  bool auto_run_ = true;
  // Watched ports per tab and mode, and what each tab was sent last (value identity).
  std::map<int, std::map<std::string, std::set<std::string>>> watches_;
  std::map<std::pair<int, std::string>, boost::shared_ptr<const void>> sent_;
  std::map<std::string, std::pair<boost::shared_ptr<const void>, std::shared_ptr<const std::string>>> encoded_;
};

}  // namespace designer
}  // namespace imagenets
