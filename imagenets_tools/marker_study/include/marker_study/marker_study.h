// The paper's marker accuracy study (5.1, Figs. 5.1 and 5.2), made reproducible, and extended with
// harder imaging. The marker at the origin, the FRIEND camera on a sphere around it (tilt 0..70 deg
// x pan 0..350 deg in 10 deg steps: 288 views), each view rendered (marker.h, marker_scene.h) under
// one imaging condition and detected with a fixed threshold (40), with the robust marker detection
// net as it is written (`detect`: what `imagenets detect` runs by default), with the calibration's
// detection net (`calibration`: config/nets/calibration_marker_detection.yaml, given the true pose
// as its prediction, as the calibration gives the nominal model's) and, as the peer, the same view
// with an AprilTag of the same size detected by libapriltag.
//
// A condition gives the range of each imaging parameter; every view draws its own values from the
// ranges (seeded, the same for the three methods). The paper's conditions are `even` (its lighting)
// and `varying` (an illumination that changes from image to image); the harder ones
// take the marker out to 1.5 m, blur it up to 2 px, add noise up to 6 gray levels and dim the scene
// down to 15 %, one at a time and all together, also in front of a dark wall; `worst` has the far
// end of every range at once in every view (1.5 m, 1.5 px, noise 5, 25 % light, dark wall), and
// `reflections` a specular highlight near the marker in every view.
//
// With `decoys`, every view is rendered a second time with a decoy in the marker's place: the same
// black-bordered square with another, random 6 x 6 pattern (for libapriltag, a tag36h11 of another
// id; for the ChArUco board, the same board of another dictionary). A detection there is a false
// positive; it measures what a lower confidence limit costs.
//
// The targets people print come as rows too (StudyConfig::tag_target, board_target): the same
// AprilTag view detected by our AprilTag target detection, and a ChArUco board of the marker's size.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include "imagenets/package_file.h"

namespace imagenets {
namespace marker {

struct StudyCondition {
  std::string name;
  double distance_min = 0.6, distance_max = 0.6;          // metres, uniform
  double blur_min = 0.7, blur_max = 0.7;                  // Gaussian blur sigma, pixels, uniform
  double noise_min = 2.0, noise_max = 2.0;                // sensor noise sigma, gray levels, uniform
  double illumination_min = 1.0, illumination_max = 1.0;  // log-uniform
  double background = 0.5;                                // wall level (before illumination)
  // A specular highlight near the marker in every view (as the simulator's reflection fault: a
  // saturating spot of 0.12..0.27 marker sides within half a side of its centre, 200..300 gray levels).
  bool reflection = false;
};

// Every condition the study knows, in table order: the paper's two, then the harder ones.
const std::vector<StudyCondition>& studyConditions();
// `names`: comma-separated condition names, or `paper` (even, varying), `hard` (the harder imaging:
// all but the paper's and `reflections`) or `all`. Throws std::invalid_argument naming an unknown name and listing the known ones.
std::vector<StudyCondition> selectConditions(const std::string& names);

struct StudyConfig {
  std::string marker = imagenets::packageFile("imagenets_vision", "config/markers/gripper.yaml");
  std::string camera = imagenets::packageFile("imagenets_vision", "config/cameras/stereo_left.yaml");
  std::string net = imagenets::packageFile("imagenets_blocks", "config/nets/robust_marker_detection.yaml");
  std::string calibration_net = imagenets::packageFile("imagenets_blocks", "config/nets/calibration_marker_detection.yaml");  // empty: not run
  double pan_from = 0, pan_to = 350, pan_step = 10;    // degrees
  double tilt_from = 0, tilt_to = 70, tilt_step = 10;  // degrees
  std::vector<StudyCondition> conditions = selectConditions("paper");
  int fixed_threshold = 40;
  int supersampling = 4;
  int threads = 0;  // parallel images; 0 = hardware threads
  unsigned seed = 2012;
  bool decoys = false;  // also run every method on a decoy of each view (false positives)
  // The targets people print, as rows beside ours (target.h): the AprilTag of the `apriltag` row
  // detected by our AprilTag target detection (`apriltag_target`: libapriltag, its squares located
  // again by our edge fit, the pose from the corners), and a ChArUco board of the marker's size in
  // the marker's place (`charuco`). Empty: that row is not run.
  std::string tag_target = imagenets::packageFile("imagenets_vision", "config/targets/apriltag_36h11_60mm.yaml");
  std::string board_target = imagenets::packageFile("imagenets_vision", "config/targets/charuco_4x4_60mm.yaml");
};

// A bounded run for tests and a first look: 12 views per condition (4 pans x 3 tilts up to 70 deg),
// supersampling 3.
void makeQuick(StudyConfig* config);

struct StudyRow {
  double pan = 0, tilt = 0;  // degrees
  std::string condition;
  double distance = 0.6, blur = 0.7, noise = 2, illumination = 1, background = 0.5;  // as rendered
  std::string method;        // fixed40 | detect | calibration | apriltag | apriltag_target | charuco
  bool found = false;
  double position_error_mm = 0, orientation_error_deg = 0;
  double threshold = 0;      // NaN for apriltag / not found
  double ms = 0;             // detection time (not rendering)
  bool decoy = false;        // the view showed a decoy: `found` is a false positive
};

struct StudySummaryRow {
  std::string method, condition;
  int images = 0, found = 0;  // views of the marker (decoys not counted)
  int decoys = 0, false_positives = 0;
  double median_mm = 0, p95_mm = 0, max_mm = 0, median_deg = 0, max_deg = 0, median_ms = 0;
};

// Runs the study; `progress(done, total)` is called after each view (from worker threads, serialised).
// Throws std::runtime_error naming the file for a bad marker, camera or net file.
std::vector<StudyRow> runStudy(const StudyConfig& config,
                               const std::function<void(int done, int total)>& progress = nullptr);
// One row per condition and method, conditions in the order they first appear.
std::vector<StudySummaryRow> summarize(const std::vector<StudyRow>& rows);

// The study's targets, per condition and for each of our two nets (`detect`, `calibration`):
// it finds at least as many markers as libapriltag and its median position error is at most half
// of libapriltag's.
struct TargetCheck {
  std::string condition, method;
  bool rate_ok = false, median_ok = false;
  bool ok() const { return rate_ok && median_ok; }
};
std::vector<TargetCheck> checkTargets(const std::vector<StudySummaryRow>& summary);

// CSV of every row (and back: throws std::runtime_error naming the line); Markdown tables: every
// method and condition, and our nets beside libapriltag per condition with the targets.
std::string toCsv(const std::vector<StudyRow>& rows);
std::vector<StudyRow> fromCsv(const std::string& csv);
std::string toMarkdown(const std::vector<StudySummaryRow>& summary, const StudyConfig& config);
std::string sideBySideMarkdown(const std::vector<StudySummaryRow>& summary);
// Fig. 5.2-style picture for one condition: position error over pan (x) and tilt (y), one panel per
// method, one logarithmic colour scale (0.01 mm .. scale_mm) shared by every panel, so that
// sub-millimetre structure and large errors show in the same picture; not found = grey with a cross.
cv::Mat errorMapImage(const std::vector<StudyRow>& rows, const std::string& condition, double scale_mm);

}  // namespace marker
}  // namespace imagenets
