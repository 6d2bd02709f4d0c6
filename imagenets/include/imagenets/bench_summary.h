// One row of the summary table that `make bench` ends with (scripts/run-benchmarks collects the
// rows of every benchmark into one printed table and out/bench/summary.csv): a figure, our value,
// the baseline or peer it is compared with, their ratio, the target and whether it is met.
// Printed as one tab-separated line starting with "SUMMARY" so the script finds it in any output.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace imagenets {

// `ours` / `baseline` NaN: not measured ("-"); `baseline` NaN also leaves the ratio out. `target`
// says in words what must hold (e.g. "<= 0.5 us/block"), `met` whether it does; an empty target
// has no verdict.
inline void printSummaryRow(const std::string& figure, double ours, double baseline, const std::string& target,
                            bool met) {
  auto number = [](double v) {
    if (!std::isfinite(v)) return std::string("-");
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%.4g", v);
    return std::string(buf);
  };
  const double ratio = std::isfinite(ours) && std::isfinite(baseline) && baseline != 0 ? ours / baseline : NAN;
  std::printf("SUMMARY\t%s\t%s\t%s\t%s\t%s\t%s\n", figure.c_str(), number(ours).c_str(), number(baseline).c_str(),
              number(ratio).c_str(), target.empty() ? "-" : target.c_str(), target.empty() ? "-" : met ? "yes" : "no");
  std::fflush(stdout);
}

}  // namespace imagenets
