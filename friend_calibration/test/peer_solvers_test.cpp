// Our calibration beside OpenCV's hand-eye solvers on the same simulated eye-to-hand samples
// (peer_study.h): in every row of the study (corner noise 0.2 / 0.5 / 1 px, 10 % bad detections,
// 5 / 10 / 20 poses) ours is at least as accurate as the best of them, in the camera's position and
// in its orientation (median over random true robots).
#include <cstdio>

#include <gtest/gtest.h>

#include "peer_study.h"

namespace imagenets_calibration {
namespace {

TEST(PeerSolvers, OursIsAtLeastAsAccurateAsTheBestOfOpenCVsHandEyeSolversInEveryRow) {
  std::vector<PeerStudyResult> results;
  for (const auto& row : peerStudyRows()) {
    results.push_back(runPeerStudy(row, 12));
    const PeerStudyResult& r = results.back();
    ASSERT_EQ(r.methods.size(), 8u);
    ASSERT_EQ(r.methods.front(), "ours");
    EXPECT_EQ(r.failures.front(), 0) << r.row.label();
    double best_mm = 1e9, best_deg = 1e9;
    std::string best_mm_by, best_deg_by;
    for (size_t m = 1; m < r.methods.size(); ++m) {
      if (r.median_mm[m] < best_mm) best_mm = r.median_mm[m], best_mm_by = r.methods[m];
      if (r.median_deg[m] < best_deg) best_deg = r.median_deg[m], best_deg_by = r.methods[m];
    }
    std::printf("%-26s ours %.3f mm / %.4f deg; best peer %.3f mm (%s) / %.4f deg (%s)\n", r.row.label().c_str(),
                r.median_mm[0], r.median_deg[0], best_mm, best_mm_by.c_str(), best_deg, best_deg_by.c_str());
    EXPECT_LE(r.median_mm[0], best_mm) << r.row.label() << ": " << best_mm_by;
    EXPECT_LE(r.median_deg[0], best_deg) << r.row.label() << ": " << best_deg_by;
  }
  std::printf("%s", peerStudyMarkdown(results).c_str());
}

}  // namespace
}  // namespace imagenets_calibration
