// The paper's marker accuracy study (5.1, Figs. 5.1 and 5.2), made reproducible: the marker at
// the origin, the FRIEND camera at 600 mm, tilt 0..70 deg x pan 0..350 deg in 10 deg steps (288
// views), each rendered (marker.h, marker_scene.h) and detected with a fixed threshold (40), with
// the feedback sweep 40..80 (the robust marker detection net), and, as the peer, the same views
// with an AprilTag of the same size detected by libapriltag. Once with the paper's even lighting
// and once with an illumination that changes from image to image.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace imagenets {
namespace marker {

struct StudyConfig {
  std::string marker = "config/markers/gripper.yaml";
  std::string camera = "config/cameras/friend_stereo_left.yaml";
  std::string net = "config/nets/robust_marker_detection.yaml";
  double distance = 0.6;                       // metres
  double pan_from = 0, pan_to = 350, pan_step = 10;    // degrees
  double tilt_from = 0, tilt_to = 70, tilt_step = 10;  // degrees
  std::vector<std::string> lightings{"even", "varying"};
  double illumination_min = 0.35, illumination_max = 2.25;  // "varying": log-uniform per image
  int fixed_threshold = 40;
  double feedback_from = 40, feedback_to = 80, feedback_step = 1;
  int supersampling = 4;
  int threads = 0;  // parallel images; 0 = hardware threads
  unsigned seed = 2012;
};

struct StudyRow {
  double pan = 0, tilt = 0;  // degrees
  std::string lighting;
  double illumination = 1;
  std::string method;        // fixed40 | feedback | apriltag
  bool found = false;
  double position_error_mm = 0, orientation_error_deg = 0;
  double threshold = 0;      // NaN for apriltag / not found
  double ms = 0;             // detection time (not rendering)
};

struct StudySummaryRow {
  std::string method, lighting;
  int images = 0, found = 0;
  double median_mm = 0, p95_mm = 0, max_mm = 0, median_deg = 0, max_deg = 0, median_ms = 0;
};

// Runs the study; `progress(done, total)` is called after each view (from worker threads, serialised).
// Throws std::runtime_error naming the file for a bad marker, camera or net file.
std::vector<StudyRow> runStudy(const StudyConfig& config,
                               const std::function<void(int done, int total)>& progress = nullptr);
std::vector<StudySummaryRow> summarize(const std::vector<StudyRow>& rows);

// CSV of every row (and back: throws std::runtime_error naming the line); Markdown table of the summary.
std::string toCsv(const std::vector<StudyRow>& rows);
std::vector<StudyRow> fromCsv(const std::string& csv);
std::string toMarkdown(const std::vector<StudySummaryRow>& summary, const StudyConfig& config);
// Fig. 5.2-style picture for one lighting: position error over pan (x) and tilt (y), one panel per
// method, one logarithmic colour scale (0.01 mm .. scale_mm) shared by every panel, so that
// sub-millimetre structure and large errors show in the same picture; not found = grey with a cross.
cv::Mat errorMapImage(const std::vector<StudyRow>& rows, const std::string& lighting, double scale_mm);

}  // namespace marker
}  // namespace imagenets
