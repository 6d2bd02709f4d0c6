// `imagenets run NET [--set block.property=value ...] [--set-all property=value ...] [--output-dir DIR] [--threads N] [--quiet]
// [--trials]`: runs a net, prints a progress line per block as it finishes (from the run events, on
// stderr), writes every output port (images as PNG, the rest as YAML) and prints per-block timings.
#include <cstdio>
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <mutex>

#include <boost/filesystem.hpp>

#include "imagenets/tool/command.h"
#include "imagenets/executor.h"
#include "imagenets/net_wide_property.h"
#include "output_writer.h"

namespace imagenets {
namespace tool {
namespace {

// Progress lines: "[k/N] block: status (ms, CPU ms)" for the net's own blocks, indented lines for blocks
// inside sub-nets ("sub/inner") and sub-net repetitions; feedback trials with `trials`.
RunObserver progressPrinter(const Net& net, bool trials) {
  auto mutex = std::make_shared<std::mutex>();
  auto finished = std::make_shared<size_t>(0);
  const size_t total = net.nodes().size();
  return [=](const RunEvent& e) {
    const bool block_done = e.kind == RunEventKind::BlockFinished || e.kind == RunEventKind::BlockCached;
    if (!block_done && e.kind != RunEventKind::Repetition && !(trials && e.kind == RunEventKind::FeedbackTrial)) return;
    std::lock_guard<std::mutex> lock(*mutex);
    if (block_done && e.block.find('/') == std::string::npos) {
      std::cerr << "[" << ++*finished << "/" << total << "] " << describe(e) << "\n";
    } else {
      std::cerr << "      " << describe(e) << "\n";
    }
  };
}

void declare(Flags& f) {
  f.add()("set", po::value<std::vector<std::string>>(),
          "block.property=value: as if written in the net file (also what a block reads when configured)")
      ("set-all", po::value<std::vector<std::string>>(),
       "property=value: for every block of the net and its sub-nets that has the property")
      ("output-dir,o", po::value<std::string>(), "write every output port here (images as PNG, others as YAML)")
      ("threads", po::value<int>()->default_value(0), "worker threads (0 = number of cores)")
      ("quiet,q", po::bool_switch(), "no progress lines")
      ("trials", po::bool_switch(), "a progress line for every feedback trial too");
  f.operand("NET", 1, "the net file");
}

// --set changes the net as if written in its file, before its blocks are made: so it also sets
// what a block reads once when it is configured (a sub-net's `net`, ...). Relative paths resolve
// against the net file, as there.
NetSpec netWithSettings(const std::string& net_path, const std::vector<std::string>& sets) {
  NetSpec spec = parseNetFile(net_path);
  for (const auto& s : sets) {
    const auto eq = s.find('='), dot = s.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq) {
      throw UsageError("--set '" + s + "' is not block.property=value");
    }
    const std::string block = s.substr(0, dot), property = s.substr(dot + 1, eq - dot - 1);
    BlockSpec* b = spec.findBlock(block);
    if (!b) throw UsageError("--set '" + s + "': " + net_path + " has no block '" + block + "'");
    b->setProperty(property, s.substr(eq + 1));
  }
  return spec;
}

// --set-all: one value for every block of the net and its sub-nets that has the property (e.g.
// the robot description every calibration block reads). Relative paths: against the working
// directory (a value for blocks of several net files).
void setAll(Executor& executor, const std::string& net_path, const std::vector<std::string>& set_alls, bool quiet) {
  for (const auto& s : set_alls) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--set-all '" + s + "' is not property=value");
    const std::string property = s.substr(0, eq);
    const auto set = setPropertyInNetTree(executor, property, s.substr(eq + 1));
    if (set.empty()) throw UsageError("--set-all '" + s + "': no block of " + net_path + " or its sub-nets has a property '" + property + "'");
    if (quiet) continue;
    std::cout << "--set-all " << property << ":";
    for (const auto& b : set) std::cout << " " << b;
    std::cout << "\n";
  }
}

void printTimings(const Executor& executor, const RunReport& report, const std::string& net_path) {
  std::cout << "net " << net_path << ": " << report.ran.size() << " blocks ran, " << report.failed.size()
            << " failed, " << report.not_run.size() << " not run (" << executor.threads() << " threads)\n";
  std::cout << "  " << std::left << std::setw(24) << "block" << std::setw(10) << "status" << std::right
            << std::setw(6) << "runs" << std::setw(12) << "last ms" << std::setw(12) << "mean ms" << std::setw(12)
            << "last CPU ms" << std::setw(12) << "mean CPU ms" << "\n";
  for (const auto& node : executor.net().nodes()) {
    BlockStats s = executor.stats(node.name);
    std::cout << "  " << std::left << std::setw(24) << node.name << std::setw(10) << statusName(s.status) << std::right
              << std::setw(6) << s.runs << std::fixed << std::setprecision(3) << std::setw(12) << s.last_ms
              << std::setw(12) << s.mean_ms << std::setw(12) << s.last_cpu_ms << std::setw(12) << s.mean_cpu_ms << "\n";
  }
  for (const auto& f : report.failed) std::cout << "FAILED " << f << "\n";
  for (const auto& n : report.not_run) std::cout << "not run: " << n << "\n";
}

void writeOutputs(const Executor& executor, const std::string& output_dir) {
  boost::filesystem::create_directories(output_dir);
  size_t written = 0;
  for (const auto& node : executor.net().nodes()) {
    for (const auto& port : node.block->outputs()) {
      Value v = executor.output(node.name + "." + port.name);
      if (!v) continue;
      std::cout << "  wrote " << writeValue(v, output_dir, node.name + "." + port.name) << "\n";
      ++written;
    }
  }
  std::cout << written << " outputs written to " << output_dir << "\n";
}

int run(const Options& o) {
  const auto nets = strings(o, "NET");
  if (nets.empty()) throw UsageError("expects a net file");
  const std::string& net_path = nets.front();
  const bool quiet = o["quiet"].as<bool>();
  ExecutorOptions options;
  options.cpu_time = true;  // the table shows it
  options.threads = o["threads"].as<int>();
  Executor executor(Net::build(netWithSettings(net_path, strings(o, "set"))), options);
  setAll(executor, net_path, strings(o, "set-all"), quiet);
  if (!quiet) executor.addObserver(progressPrinter(executor.net(), o["trials"].as<bool>()));
  const RunReport report = executor.run();
  printTimings(executor, report, net_path);
  if (o.count("output-dir")) writeOutputs(executor, o["output-dir"].as<std::string>());
  return report.ok() ? 0 : 1;
}

}  // namespace

IMAGENETS_TOOL_COMMAND(run, "run",
                       "run NET [--set block.property=value ...] [--set-all property=value ...] [--output-dir DIR] [--threads N] "
                       "[--quiet] [--trials]",
                       "run a net, showing progress (--trials: every feedback trial); write its outputs (images as "
                       "PNG, others as YAML); print timings",
                       declare, run);

}  // namespace tool
}  // namespace imagenets
