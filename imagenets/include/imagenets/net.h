// Nets: blocks plus links (output port -> input port), described in YAML and checked when built.
//
//   blocks:
//     source:    {type: imagenets/ImageFileSource, properties: {path: ../images/scene.png}}
//     gray:      {type: imagenets/Grayscale}
//     threshold: {type: imagenets/Threshold, properties: {threshold: 60}}
//   links:
//     - source.image -> gray.image
//     - gray.image -> threshold.image
//
// The same schema loads from a file or from a rosparam namespace (see the nodelet host).
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "imagenets/block.h"

namespace imagenets {

struct SourceLocation {
  std::string file;
  int line = 0;  // 1-based; 0 when unknown
  std::string str() const;  // "file:line" (or just "file")
};

// Every load error, each naming file, block, port or property and the offending value.
class NetError : public std::runtime_error {
 public:
  explicit NetError(std::vector<std::string> errors);
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  std::vector<std::string> errors_;
};

struct PropertySetting {
  std::string name;
  std::string text;  // as written: YAML scalar or flow sequence
  SourceLocation loc;
};

// Feedback (paper 3.4): tune one numeric property of the block to maximise (or minimise) a
// score port downstream. feedback_search.h decides which candidates are tried, in what order.
struct FeedbackInitial {
  double value = 0.0;      // a constant first candidate ...
  std::string block, port; // ... or the value of another block's std_msgs/Float64 output
  bool fromPort() const { return !block.empty(); }
  std::string str() const;  // "otsu.threshold" or the number
};

struct FeedbackSpec {
  std::string property;
  std::vector<double> values;  // the candidates, from `from/to/step` or an explicit list
  std::optional<double> from, to, step;  // when given as a range
  std::string score_block, score_port;
  bool maximize = true;
  std::string search = "exhaustive";  // or "coarse_to_fine"
  bool parallel = true;               // trials run in parallel on the thread pool
  std::vector<FeedbackInitial> initial;       // tried first, in this order
  std::optional<double> good_enough;          // stop at the first score at least (minimize: at most) this
  std::optional<double> coarse_step, fine_radius;  // coarse_to_fine with an explicit grid
  SourceLocation loc;
};

struct BlockSpec {
  std::string name;
  std::string type;
  std::vector<PropertySetting> properties;
  std::optional<FeedbackSpec> feedback;
  SourceLocation loc;

  // The setting of a property as written, or null when the block takes the default.
  const PropertySetting* findSetting(const std::string& property) const;
  // Sets a property as if written in the net file (text as there: "72", "[1, 2]", a path); a new
  // setting takes the block's location. Checked when the net is built.
  void setProperty(const std::string& property, const std::string& text);
  // Drops the setting (the property takes its default); false when there was none.
  bool removeProperty(const std::string& property);
};

struct LinkSpec {
  std::string from_block, from_port, to_block, to_port;
  SourceLocation loc;
};

struct NetSpec {
  std::string origin;    // file path or rosparam namespace, for messages
  std::string base_dir;  // relative paths in properties resolve against it
  std::vector<std::string> include_chain;  // files including this one (sub-nets), outermost first
  std::vector<BlockSpec> blocks;
  std::vector<LinkSpec> links;

  // The block of that name, or null.
  BlockSpec* findBlock(const std::string& name);
  const BlockSpec* findBlock(const std::string& name) const;
  // The block of that name; throws NetError "<origin>: no block named 'x'".
  BlockSpec& block(const std::string& name);
  const BlockSpec& block(const std::string& name) const;
  // Removes a block with what refers to it: its links, a feedback scored by it, feedback initial
  // values taken from it. False when there is no such block.
  bool removeBlock(const std::string& name);
};

// Parse only (no blocks created). Throw NetError for unreadable or malformed input.
NetSpec parseNetFile(const std::string& path);
NetSpec parseNetText(const std::string& yaml, const std::string& origin, const std::string& base_dir);

// The net being built on this thread: lets a block's configure() resolve files relative to the
// net file and see the chain of including files (sub-nets use it to refuse self-inclusion).
class LoadContext {
 public:
  static const NetSpec* current();  // null outside Net::build
  class Scope {
   public:
    explicit Scope(const NetSpec& spec);
    ~Scope();

   private:
    const NetSpec* previous_;
  };
};

struct Endpoint {
  int node = -1;
  int port = -1;
  bool valid() const { return node >= 0; }
};

// A built net: blocks instantiated and configured, links resolved and type-checked, acyclic.
class Net {
 public:
  struct Node {
    std::string name;
    std::unique_ptr<Block> block;
    SourceLocation loc;
    std::vector<Endpoint> input_links;  // per input port: the linked output, or invalid
    std::vector<int> downstream;        // nodes fed by this one (unique)
    std::optional<FeedbackSpec> feedback;
  };

  // Builds and validates (NetBuilder's steps); throws NetError listing every problem found.
  // Nothing half-built survives a failed load.
  static std::unique_ptr<Net> build(const NetSpec& spec);
  static std::unique_ptr<Net> loadFile(const std::string& path);

  const std::string& origin() const { return origin_; }
  const std::string& baseDir() const { return base_dir_; }
  const std::vector<std::string>& includeChain() const { return include_chain_; }
  const std::vector<Node>& nodes() const { return nodes_; }
  Node& node(int i) { return nodes_[i]; }
  const Node& node(int i) const { return nodes_[i]; }
  int findNode(const std::string& name) const;  // -1 if none
  const std::vector<int>& topologicalOrder() const { return order_; }
  // "block.port" -> endpoint; throws NetError naming what is missing.
  Endpoint resolveOutput(const std::string& block_port) const;
  Endpoint resolveInput(const std::string& block_port) const;
  // All nodes reachable downstream of `from` (excluding it).
  std::vector<int> descendants(int from) const;

 private:
  friend class NetBuilder;  // the steps of build() fill the net
  std::string origin_, base_dir_;
  std::vector<std::string> include_chain_;
  std::vector<Node> nodes_;
  std::vector<int> order_;
};

}  // namespace imagenets
