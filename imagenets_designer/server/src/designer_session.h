// The Designer's requests (designer/PROTOCOL.md), apart from any network code: each request is
// read, handed to the part that does it (edits of the NetDocument, undo in the EditHistory, the
// LiveNet that runs it, the NetFiles) and answered. The server calls handle() for one request at
// a time (from its worker thread) and cancel() from any thread; the session answers through an
// Output.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "designer_output.h"
#include "edit_history.h"
#include "live_net.h"
#include "net_document.h"
#include "net_files.h"
#include "request_error.h"

namespace imagenets {
namespace designer {

class DesignerSession {
 public:
  using Output = DesignerOutput;

  struct Options {
    std::vector<std::string> roots;  // besides the net's folder and the package's config/
    int threads = 0;                 // executor threads (0 = cores)
  };

  DesignerSession(Output& output, Options options);

  // Loads the net given on the command line (a file that does not exist yet: a new net saved
  // under that name). A net that does not load leaves an empty net with the errors in the net
  // state (and returns false).
  bool openStartupNet(const std::string& path);

  // One request (a JSON object with "op" and "id"); the reply goes to `client`.
  void handle(int client, const nlohmann::json& request);
  // Stops the run in progress, if any (any thread).
  void cancel() { live_.cancel(); }
  void disconnected(int client) { live_.disconnected(client); }

  const AllowedRoots& roots() const { return files_.roots(); }
  std::string fileName() const { return file_; }
  // The current net state (the `net` push).
  nlohmann::json netState() const;

 private:
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

  // Makes `next` the edited net as one undo step (see EditHistory::edited), and the new state
  // to every tab; `notify` false: the caller pushes the state later (after an automatic run).
  // Throws NetError (nothing changed) when the engine refuses it.
  void apply(NetDocument next, const std::string& merge = "", bool notify = true);
  nlohmann::json step(EditHistory::Direction direction);
  // An empty net in `dir`, named `origin` (a file not saved yet, or none).
  void startEmpty(const std::string& origin, const std::string& dir);
  void loadFile(const std::string& path);  // throws NetError; not an undo step
  nlohmann::json runAndReport(LiveNet::RunKind kind, const std::string& block = "");
  void changed();  // revision++, push the net state
  nlohmann::json portDataHeader() const;
  std::string baseDir() const { return doc_.spec.base_dir; }

  Output& out_;
  NetFiles files_;
  NetDocument doc_;
  LiveNet live_;
  EditHistory history_;
  std::string file_;  // "" for a net never saved
  std::string saved_text_;
  std::vector<std::string> errors_;
  long revision_ = 0;
  // Counts the nets opened (a file, a sub-net's file): what a page shows of one net (previews,
  // run results) must not carry over to another, even one with the same block names.
  long document_ = 0;
  bool auto_run_ = true;
};

}  // namespace designer
}  // namespace imagenets
