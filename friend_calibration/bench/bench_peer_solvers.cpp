// bench_peer_solvers: our calibration beside OpenCV's hand-eye solvers (calibrateHandEye: Tsai,
// Park, Horaud, Andreff, Daniilidis; calibrateRobotWorldHandEye: Shah, Li) on the same simulated
// eye-to-hand samples (friend_calibration/test/peer_study.h): median error of the camera's pose in
// the base frame over random true robots, per row of corner noise, bad detections and poses.
// `bench_peer_solvers [TRIALS]` (default 50).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "imagenets/bench_summary.h"
#include "peer_study.h"

using namespace imagenets_calibration;

int main(int argc, char** argv) {
  const int trials = argc > 1 ? std::atoi(argv[1]) : 50;
  std::vector<PeerStudyResult> results;
  for (const auto& row : peerStudyRows()) {
    results.push_back(runPeerStudy(row, trials));
    const auto& r = results.back();
    std::printf("%-28s", r.row.label().c_str());
    for (size_t m = 0; m < r.methods.size(); ++m) {
      std::printf("  %s %.2f mm / %.3f deg (max %.2f / %.3f)", r.methods[m].c_str(), r.median_mm[m], r.median_deg[m],
                  r.max_mm[m], r.max_deg[m]);
    }
    std::printf("\n");
    // Ours (first) against the best of the OpenCV peers in this row.
    size_t best = 1;
    for (size_t m = 2; m < r.methods.size(); ++m) {
      if (r.median_mm[m] < r.median_mm[best]) best = m;
    }
    if (r.methods.size() > 1) {
      imagenets::printSummaryRow("hand-eye, median camera error mm, ours vs best OpenCV peer (" + r.methods[best] +
                                     "): " + r.row.label(),
                                 r.median_mm[0], r.median_mm[best], "", false);
    }
    std::fflush(stdout);
  }
  std::printf("\nMedian error of the camera pose over %d random true robots per row:\n\n%s", trials,
              peerStudyMarkdown(results).c_str());
  return 0;
}
