// Our calibration beside the solvers everybody has (imagenets_calibration/hand_eye_peers.h:
// OpenCV's calibrateHandEye, Tsai Park Horaud Andreff Daniilidis, and calibrateRobotWorldHandEye,
// Shah Li) on the same simulated samples, for the eye-to-hand case: FRIEND's head holds still at its
// calibration pose (the camera does not move during the samples) and the arm shows the gripper
// marker in varied poses. A random true robot per trial (the simulator's drawing: head mount and
// marker offset; the joint zero offsets zero, so that no method meets an error it cannot model);
// the marker's 8 points projected through the true geometry and the left camera's model with
// Gaussian corner noise, each detection's pose fitted to its points (IPPE + LM through the camera
// model, as the detector does); a bad detection has 2 of its 8 points moved 3 px (a reflection on
// an edge). Every method gets every detection; ours (calibrate(), joint method: 3D-point solve,
// then the pixel-level bundle adjustment) its points as well. The error: the left camera's pose in
// the base frame against the truth. Shared by peer_solvers_test.cpp and bench_peer_solvers.
#pragma once

#include <string>
#include <vector>

namespace imagenets_calibration {

struct PeerStudyRow {
  double noise_px = 0.5;
  int poses = 10;
  double bad_fraction = 0.0;  // share of the detections made bad (rounded, at least 1 when > 0)
  std::string label() const;
};

struct PeerStudyResult {
  PeerStudyRow row;
  int trials = 0;
  std::vector<std::string> methods;  // "ours" first, then the peers in hand_eye_peers.h's order
  // Per method, over the trials: median and largest camera error (mm, deg); failures (no result).
  std::vector<double> median_mm, median_deg, max_mm, max_deg;
  std::vector<int> failures;
};

// The six rows of the study: 0.2 / 0.5 / 1 px at 10 poses; 10 % bad detections (0.5 px, 20
// poses: 2 bad); 5 and 20 poses at 0.5 px.
std::vector<PeerStudyRow> peerStudyRows();
// One row over `trials` random true robots (seeds 1..trials).
PeerStudyResult runPeerStudy(const PeerStudyRow& row, int trials);
// A Markdown table of the rows: per method median (max) camera error, mm / deg.
std::string peerStudyMarkdown(const std::vector<PeerStudyResult>& results);

}  // namespace imagenets_calibration
