// The marker accuracy study (see marker_study.h).
#include "marker_study/marker_study.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <boost/make_shared.hpp>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/imgproc.hpp>

#include "imagenets/vision/apriltag_marker.h"
#include "imagenets/vision/marker.h"
#include "imagenets/vision/marker_msgs.h"
#include "marker_study/marker_net.h"
#include "imagenets/vision/marker_scene.h"
#include "imagenets/vision/target.h"
#include "imagenets/vision/read_camera_info.h"
#include "imagenets/executor.h"
#include "imagenets/vision/frames.h"
#include <geometry_msgs/PoseStamped.h>
#include <imagenets/MarkerDetection.h>

namespace imagenets {
namespace marker {

namespace {

const double kDeg = M_PI / 180.0;

std::vector<double> range(double from, double to, double step) {
  std::vector<double> v;
  for (double x = from; x <= to + 1e-9; x += step) v.push_back(x);
  return v;
}

struct View {
  double pan, tilt;
  const StudyCondition* condition;
  double distance, blur, noise, illumination;
  std::uint64_t seed;
  double highlight = 0, highlight_sigma = 0;  // gray levels, marker sides (StudyCondition::reflection)
  cv::Point2d highlight_offset;
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(pos));
  const size_t j = std::min(i + 1, v.size() - 1);
  return v[i] + (v[j] - v[i]) * (pos - i);
}

// The marker with a random 6 x 6 pattern in place of its own: a decoy, as another marker of the
// same kind (or any black-framed square with something inside) would be.
MarkerDescription withRandomPattern(const MarkerDescription& marker, std::mt19937_64* rng) {
  cv::Mat cells(6, 6, CV_8UC1);
  for (int i = 0; i < 36; ++i) cells.at<uchar>(i / 6, i % 6) = ((*rng)() & 1) ? 255 : 0;
  MarkerDescription decoy = marker;
  decoy.pattern = cv::Mat();  // its own pixels, not the marker's (cv::Mat copies share them)
  cv::resize(cells, decoy.pattern, marker.pattern.size(), 0, 0, cv::INTER_NEAREST);
  return decoy;
}

}  // namespace

const std::vector<StudyCondition>& studyConditions() {
  static const std::vector<StudyCondition> all = [] {
    std::vector<StudyCondition> c;
    auto add = [&](const std::string& name) -> StudyCondition& {
      c.emplace_back();
      c.back().name = name;
      return c.back();
    };
    add("even");  // the paper's: 600 mm, blur 0.7 px, noise 2, illumination 1
    add("varying").illumination_min = 0.35;
    c.back().illumination_max = 2.25;
    add("far").distance_max = 1.5;  // 0.6..1.5 m
    add("blur").blur_max = 2.0;     // 0.7..2 px
    add("noise").noise_max = 6.0;   // 2..6 gray levels
    add("dim").illumination_min = 0.15;  // 15 %..50 %
    c.back().illumination_max = 0.5;
    StudyCondition& dark = add("dim_dark_wall");  // the black border next to a dark wall
    dark.illumination_min = 0.15;
    dark.illumination_max = 0.5;
    dark.background = 0.1;
    StudyCondition& hard = add("combined");  // everything at once
    hard.distance_max = 1.5;
    hard.blur_max = 2.0;
    hard.noise_max = 6.0;
    hard.illumination_min = 0.15;
    hard.illumination_max = 1.0;
    hard.background = 0.1;
    // The worst of `combined` in every view at once: far, blurred, noisy and dim together.
    StudyCondition& worst = add("worst");
    worst.distance_min = worst.distance_max = 1.5;
    worst.blur_min = worst.blur_max = 1.5;
    worst.noise_min = worst.noise_max = 5.0;
    worst.illumination_min = worst.illumination_max = 0.25;
    worst.background = 0.1;
    add("reflections").reflection = true;  // the paper's imaging and a lamp's glare on the print
    return c;
  }();
  return all;
}

std::vector<StudyCondition> selectConditions(const std::string& names) {
  const auto& all = studyConditions();
  std::vector<StudyCondition> out;
  auto add = [&](const StudyCondition& c) {
    for (const auto& o : out) {
      if (o.name == c.name) return;
    }
    out.push_back(c);
  };
  std::stringstream list(names);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "all" || name == "paper" || name == "hard") {
      for (size_t i = 0; i < all.size(); ++i) {
        const bool paper = i < 2;
        // Reflections are no harder imaging but a disturbance: by name or with `all` only.
        if (name == "all" || (name == "paper" && paper) || (name == "hard" && !paper && !all[i].reflection)) add(all[i]);
      }
      continue;
    }
    const auto it = std::find_if(all.begin(), all.end(), [&](const StudyCondition& c) { return c.name == name; });
    if (it == all.end()) {
      std::string known = "paper, hard, all";
      for (const auto& c : all) known += ", " + c.name;
      throw std::invalid_argument("marker study condition '" + name + "' is unknown (known: " + known + ")");
    }
    add(*it);
  }
  if (out.empty()) throw std::invalid_argument("marker study: no condition given in '" + names + "'");
  return out;
}

void makeQuick(StudyConfig* config) {
  config->pan_from = 15;
  config->pan_to = 285;
  config->pan_step = 90;  // 4 pans
  config->tilt_from = 0;
  config->tilt_to = 70;
  config->tilt_step = 35;  // 3 tilts, up to the steepest
  config->supersampling = 3;
}

namespace {

// The views of every condition, each with its random imaging drawn.
std::vector<View> drawViews(const StudyConfig& config) {
  std::vector<View> views;
  const auto& catalogue = studyConditions();
  for (const StudyCondition& condition : config.conditions) {
    // Each condition draws from its own seeded stream: adding or removing one changes no other's views.
    const size_t index = static_cast<size_t>(
        std::find_if(catalogue.begin(), catalogue.end(), [&](const StudyCondition& c) { return c.name == condition.name; }) -
        catalogue.begin());
    std::mt19937_64 rng(config.seed + index);
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    for (double tilt : range(config.tilt_from, config.tilt_to, config.tilt_step)) {
      for (double pan : range(config.pan_from, config.pan_to, config.pan_step)) {
        View v{pan, tilt, &condition, 0, 0, 0, 0, 0};
        v.illumination = std::exp(uniform(std::log(condition.illumination_min), std::log(condition.illumination_max)));
        v.distance = uniform(condition.distance_min, condition.distance_max);
        v.blur = uniform(condition.blur_min, condition.blur_max);
        v.noise = uniform(condition.noise_min, condition.noise_max);
        v.seed = rng();
        if (condition.reflection) {  // drawn after the rest: the other conditions' views stay as they were
          v.highlight_offset = cv::Point2d(uniform(-0.5, 0.5), uniform(-0.5, 0.5));
          v.highlight_sigma = uniform(0.12, 0.27);
          v.highlight = uniform(200, 300);
        }
        views.push_back(v);
      }
    }
  }
  return views;
}

// What the study renders, shared by its workers.
struct StudyScene {
  MarkerDescription marker;
  sensor_msgs::CameraInfoPtr info;
  render::CameraModel camera;
  std::shared_ptr<const render::Renderer> renderer;
  AprilTagOptions april;
  render::Plane square, tag;
  // The targets people print (empty when not studied), the board's plane and its decoy's.
  std::shared_ptr<const target::TargetDescription> tag_target, board_target, board_decoy;
  render::Plane board, decoy_board;

  explicit StudyScene(const StudyConfig& config)
      : marker(MarkerDescription::load(config.marker)),
        info(boost::make_shared<sensor_msgs::CameraInfo>(readCameraInfo(config.camera))),
        camera(render::CameraModel::fromCameraInfo(*info)),
        renderer(sharedRenderer(camera, config.supersampling)) {
    info->header.frame_id = "camera_optical_frame";
    square = markerPlane(marker, Eigen::Isometry3d::Identity());
    applyPrintReflectance(&square);
    april.size = marker.size;
    april.id = 0;
    tag = aprilTagPlane(april, 0, marker.margin, Eigen::Isometry3d::Identity());
    applyPrintReflectance(&tag);
    if (!config.tag_target.empty()) {
      tag_target = std::make_shared<const target::TargetDescription>(target::TargetDescription::load(config.tag_target));
      if (tag_target->type != target::TargetType::AprilTag || tag_target->family != april.family ||
          tag_target->id != 0 || tag_target->rows * tag_target->cols != 1 || std::abs(tag_target->size - april.size) > 1e-9) {
        throw std::runtime_error(config.tag_target + ": the study's AprilTag row needs one " + april.family +
                                 " tag of id 0 and the marker's size, " + std::to_string(april.size) + " m");
      }
    }
    if (!config.board_target.empty()) {
      board_target = std::make_shared<const target::TargetDescription>(target::TargetDescription::load(config.board_target));
      if (board_target->type != target::TargetType::Charuco) {
        throw std::runtime_error(config.board_target + ": the study's board row needs a charuco target, not " +
                                 board_target->typeName());
      }
      board = board_target->plane(Eigen::Isometry3d::Identity());
      applyPrintReflectance(&board);
      // The decoy: the same board with the markers of another dictionary.
      target::TargetDescription other = *board_target;
      other.dictionary = other.dictionary.rfind("DICT_4X4", 0) == 0 ? "DICT_5X5_1000" : "DICT_4X4_1000";
      board_decoy = std::make_shared<const target::TargetDescription>(other);
      decoy_board = board_decoy->plane(Eigen::Isometry3d::Identity());
      applyPrintReflectance(&decoy_board);
    }
  }
};

ThresholdMode fixedMode(const StudyConfig& config) {
  ThresholdMode mode;
  mode.kind = ThresholdMode::Kind::Fixed;
  mode.fixed = config.fixed_threshold;
  return mode;
}

ThresholdMode feedbackMode() {
  ThresholdMode mode;
  mode.kind = ThresholdMode::Kind::AsWritten;  // what `imagenets detect` runs
  mode.parallel = false;                       // the views run in parallel already
  return mode;
}

// One worker's methods: renders a view and runs every method on it, one row each.
class ViewMeasurement {
 public:
  ViewMeasurement(const StudyConfig& config, const StudyScene& scene)
      : config_(config),
        scene_(scene),
        fixed_name_("fixed" + std::to_string(config.fixed_threshold)),
        fixed_net_(config.net, config.marker, fixedMode(config), 1),
        feedback_net_(config.net, config.marker, feedbackMode(), 1),
        calibration_net_(config.calibration_net.empty() ? nullptr : Executor::loadFile(config.calibration_net)),
        april_detector_(scene.april) {}

  std::vector<StudyRow> measure(const View& v) {
    ViewSettings settings;
    settings.distance = v.distance;
    settings.pan = v.pan * kDeg;
    settings.tilt = v.tilt * kDeg;
    settings.illumination = v.illumination;
    settings.background = v.condition->background;
    settings.blur = v.blur;
    settings.noise = v.noise;
    settings.seed = v.seed;
    settings.highlight = v.highlight;
    settings.highlight_offset = v.highlight_offset;
    settings.highlight_sigma = v.highlight_sigma;
    settings.marker_size = scene_.marker.size;
    std::vector<StudyRow> rows;
    const cv::Mat square_image = renderView(*scene_.renderer, scene_.square, settings, &truth_);
    const cv::Mat board_image =
        scene_.board_target ? renderView(*scene_.renderer, scene_.board, settings, nullptr) : cv::Mat();
    measureRendering(v, square_image, renderView(*scene_.renderer, scene_.tag, settings, nullptr), board_image, false,
                     &rows);
    if (config_.decoys) {
      std::mt19937_64 decoy_rng(v.seed ^ 0x5eedDec0ull);
      render::Plane decoy_square =
          markerPlane(withRandomPattern(scene_.marker, &decoy_rng), Eigen::Isometry3d::Identity());
      applyPrintReflectance(&decoy_square);
      // tag36h11 has 587 codes; the detector looks for id 0.
      render::Plane decoy_tag = aprilTagPlane(scene_.april, 1 + static_cast<int>(decoy_rng() % 586),
                                              scene_.marker.margin, Eigen::Isometry3d::Identity());
      applyPrintReflectance(&decoy_tag);
      measureRendering(v, renderView(*scene_.renderer, decoy_square, settings, nullptr),
                       renderView(*scene_.renderer, decoy_tag, settings, nullptr),
                       scene_.board_target ? renderView(*scene_.renderer, scene_.decoy_board, settings, nullptr) : cv::Mat(),
                       true, &rows);
    }
    return rows;
  }

 private:
  // Every method on one rendering of the view (of the marker, or of a decoy in its place).
  void measureRendering(const View& v, const cv::Mat& square_view, const cv::Mat& tag_view, const cv::Mat& board_view,
                        bool decoy, std::vector<StudyRow>* rows) {
    std_msgs::Header header;
    header.frame_id = scene_.info->header.frame_id;
    const sensor_msgs::ImageConstPtr msg = cv_bridge::CvImage(header, "mono8", square_view).toImageMsg();
    for (MarkerDetectionNet* net : {&fixed_net_, &feedback_net_}) {
      StudyRow r = row(v, net == &fixed_net_ ? fixed_name_ : "detect", decoy);
      const MarkerDetectionNet::Result res = net->run(msg, scene_.info);
      if (!res.error.empty()) throw std::runtime_error(res.error);
      r.ms = res.ms;
      r.found = res.detection->found;
      if (r.found) {
        r.threshold = res.detection->threshold;
        score(&r, fromPoseMsg(res.detection->pose));
      }
      rows->push_back(r);
    }
    if (calibration_net_) rows->push_back(runCalibrationNet(row(v, "calibration", decoy), header, msg));
    StudyRow r = row(v, "apriltag", decoy);
    const auto t0 = std::chrono::steady_clock::now();
    const Detection d = april_detector_.detect(tag_view, scene_.camera);
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.found = d.found;
    if (d.found) score(&r, d.pose);
    rows->push_back(r);
    // The targets people print: the same tag view through our AprilTag target detection, and the
    // ChArUco board's view.
    if (scene_.tag_target) rows->push_back(runTarget(row(v, "apriltag_target", decoy), *scene_.tag_target, tag_view));
    if (scene_.board_target) rows->push_back(runTarget(row(v, "charuco", decoy), *scene_.board_target, board_view));
  }

  StudyRow runTarget(StudyRow r, const target::TargetDescription& t, const cv::Mat& view) {
    const auto t0 = std::chrono::steady_clock::now();
    const target::TargetDetection d = target::detectTarget(view, scene_.camera, t);
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.found = d.found;
    if (d.found) score(&r, d.pose);
    return r;
  }

  // The calibration's detection net, told where the marker truly is (the study measures the
  // detection, not the prediction).
  StudyRow runCalibrationNet(StudyRow r, const std_msgs::Header& header, const sensor_msgs::ImageConstPtr& msg) {
    auto predicted = boost::make_shared<geometry_msgs::PoseStamped>();
    predicted->header = header;
    predicted->pose = frames::toPose(truth_);
    const auto t0 = std::chrono::steady_clock::now();
    calibration_net_->setInput("image.value", msg);
    calibration_net_->setInput("camera_info.value", sensor_msgs::CameraInfoConstPtr(scene_.info));
    calibration_net_->setInput("predicted_pose.value", geometry_msgs::PoseStampedConstPtr(predicted));
    const RunReport report = calibration_net_->run();
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const auto region = calibration_net_->output<FeedbackTrace>("region.feedback_trace");
    const auto trace = calibration_net_->output<FeedbackTrace>("feedback_trace.value");
    const auto detection = calibration_net_->output<imagenets::MarkerDetection>("detection.value");
    // No region and threshold of the search found it: "no valid candidate", not an error.
    if (!report.ok() && !(region && !region->found)) {
      throw std::runtime_error(config_.calibration_net + ": " + report.failed.front());
    }
    r.found = report.ok() && detection && detection->found;
    if (r.found) {
      r.threshold = trace->chosen_value;
      score(&r, fromPoseMsg(detection->pose));
    }
    return r;
  }

  static StudyRow row(const View& v, const std::string& method, bool decoy) {
    StudyRow r;
    r.pan = v.pan;
    r.tilt = v.tilt;
    r.condition = v.condition->name;
    r.distance = v.distance;
    r.blur = v.blur;
    r.noise = v.noise;
    r.illumination = v.illumination;
    r.background = v.condition->background;
    r.method = method;
    r.threshold = std::numeric_limits<double>::quiet_NaN();
    r.decoy = decoy;
    return r;
  }

  void score(StudyRow* r, const Eigen::Isometry3d& pose) const {
    r->position_error_mm = 1000.0 * (pose.translation() - truth_.translation()).norm();
    r->orientation_error_deg = rotationAngle(pose, truth_) / kDeg;
  }

  const StudyConfig& config_;
  const StudyScene& scene_;
  const std::string fixed_name_;
  MarkerDetectionNet fixed_net_, feedback_net_;
  const std::unique_ptr<Executor> calibration_net_;
  const AprilTagDetector april_detector_;
  Eigen::Isometry3d truth_ = Eigen::Isometry3d::Identity();  // the marker's pose in the view being measured
};

}  // namespace

std::vector<StudyRow> runStudy(const StudyConfig& config, const std::function<void(int, int)>& progress) {
  const StudyScene scene(config);
  const std::vector<View> views = drawViews(config);
  // Built once here so a bad net file fails before any thread starts.
  { MarkerDetectionNet check(config.net, config.marker, feedbackMode(), 1); }
  if (!config.calibration_net.empty()) Executor::loadFile(config.calibration_net);

  std::vector<std::vector<StudyRow>> results(views.size());
  std::atomic<size_t> next{0};
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  std::string first_error;
  auto worker = [&]() {
    try {
      ViewMeasurement measurement(config, scene);
      for (size_t i; (i = next++) < views.size();) {
        results[i] = measurement.measure(views[i]);
        const int n = ++done;
        if (progress) {
          std::lock_guard<std::mutex> lock(progress_mutex);
          progress(n, static_cast<int>(views.size()));
        }
      }
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      if (first_error.empty()) first_error = e.what();
      next = views.size();
    }
  };
  int threads = config.threads > 0 ? config.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  if (!first_error.empty()) throw std::runtime_error("marker study: " + first_error);

  std::vector<StudyRow> rows;
  for (const auto& r : results) rows.insert(rows.end(), r.begin(), r.end());
  return rows;
}

std::vector<StudySummaryRow> summarize(const std::vector<StudyRow>& rows) {
  std::vector<std::string> conditions, methods;  // in the order they first appear
  for (const auto& r : rows) {
    if (std::find(conditions.begin(), conditions.end(), r.condition) == conditions.end()) conditions.push_back(r.condition);
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  std::vector<StudySummaryRow> out;
  for (const auto& condition : conditions) {
    for (const auto& method : methods) {
      StudySummaryRow s;
      s.method = method;
      s.condition = condition;
      std::vector<double> mm, deg, ms;
      for (const auto& r : rows) {
        if (r.method != method || r.condition != condition) continue;
        if (r.decoy) {
          ++s.decoys;
          s.false_positives += r.found ? 1 : 0;
          continue;
        }
        ++s.images;
        ms.push_back(r.ms);
        if (!r.found) continue;
        ++s.found;
        mm.push_back(r.position_error_mm);
        deg.push_back(r.orientation_error_deg);
      }
      if (s.images == 0) continue;
      s.median_mm = percentile(mm, 0.5);
      s.p95_mm = percentile(mm, 0.95);
      s.max_mm = percentile(mm, 1.0);
      s.median_deg = percentile(deg, 0.5);
      s.max_deg = percentile(deg, 1.0);
      s.median_ms = percentile(ms, 0.5);
      out.push_back(s);
    }
  }
  return out;
}

namespace {

const StudySummaryRow* findSummary(const std::vector<StudySummaryRow>& summary, const std::string& condition,
                                   const std::string& method) {
  for (const auto& s : summary) {
    if (s.condition == condition && s.method == method) return &s;
  }
  return nullptr;
}

bool anyDecoys(const std::vector<StudySummaryRow>& summary) {
  return std::any_of(summary.begin(), summary.end(), [](const StudySummaryRow& s) { return s.decoys > 0; });
}

}  // namespace

std::vector<TargetCheck> checkTargets(const std::vector<StudySummaryRow>& summary) {
  std::vector<TargetCheck> out;
  for (const auto& s : summary) {
    if (s.method != "detect" && s.method != "calibration") continue;
    const StudySummaryRow* april = findSummary(summary, s.condition, "apriltag");
    if (!april) continue;
    TargetCheck t;
    t.condition = s.condition;
    t.method = s.method;
    t.rate_ok = s.found * april->images >= april->found * s.images;  // rates compared without rounding
    // Nothing found by libapriltag leaves no median to halve: then any median of ours counts.
    t.median_ok = s.found > 0 && (april->found == 0 || s.median_mm <= 0.5 * april->median_mm);
    out.push_back(t);
  }
  return out;
}

std::string toCsv(const std::vector<StudyRow>& rows) {
  std::ostringstream os;
  os << "pan_deg,tilt_deg,condition,distance_m,blur_px,noise,illumination,background,method,found,position_error_mm,"
        "orientation_error_deg,threshold,time_ms,decoy\n";
  os << std::fixed;
  for (const auto& r : rows) {
    os << std::setprecision(0) << r.pan << "," << r.tilt << "," << r.condition << "," << std::setprecision(3)
       << r.distance << "," << r.blur << "," << r.noise << "," << r.illumination << "," << r.background << ","
       << r.method << "," << (r.found ? 1 : 0) << ",";
    if (r.found) os << std::setprecision(4) << r.position_error_mm << "," << r.orientation_error_deg << ",";
    else os << ",,";
    if (std::isfinite(r.threshold)) os << std::setprecision(0) << r.threshold;
    os << "," << std::setprecision(2) << r.ms << "," << (r.decoy ? 1 : 0) << "\n";
  }
  return os.str();
}

std::vector<StudyRow> fromCsv(const std::string& csv) {
  const size_t kFields = 15;  // 14 in files written before the decoy column: no decoys
  std::vector<StudyRow> rows;
  std::istringstream in(csv);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    if (++n == 1 || line.empty()) continue;  // header
    std::vector<std::string> f;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    if (f.size() == kFields - 2 && line.back() == ',') f.push_back("");
    if (f.size() == kFields - 1) f.push_back("0");
    if (f.size() != kFields) {
      throw std::runtime_error("study CSV line " + std::to_string(n) + ": expected " + std::to_string(kFields) +
                               " fields, found " + std::to_string(f.size()));
    }
    try {
      StudyRow r;
      r.pan = std::stod(f[0]);
      r.tilt = std::stod(f[1]);
      r.condition = f[2];
      r.distance = std::stod(f[3]);
      r.blur = std::stod(f[4]);
      r.noise = std::stod(f[5]);
      r.illumination = std::stod(f[6]);
      r.background = std::stod(f[7]);
      r.method = f[8];
      r.found = f[9] == "1";
      if (r.found) {
        r.position_error_mm = std::stod(f[10]);
        r.orientation_error_deg = std::stod(f[11]);
      }
      r.threshold = f[12].empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(f[12]);
      r.ms = f[13].empty() ? 0.0 : std::stod(f[13]);
      r.decoy = f[14] == "1";
      rows.push_back(r);
    } catch (const std::logic_error&) {
      throw std::runtime_error("study CSV line " + std::to_string(n) + ": bad number");
    }
  }
  return rows;
}

std::string toMarkdown(const std::vector<StudySummaryRow>& summary, const StudyConfig& config) {
  const bool decoys = anyDecoys(summary);
  std::ostringstream os;
  os << "| condition | method | detected | median pos. error mm | p95 mm | max mm | median orient. error deg | max deg | median time ms |"
     << (decoys ? " false positives on decoys |\n" : "\n");
  os << "|---|---|---|---|---|---|---|---|---|" << (decoys ? "---|\n" : "\n");
  os << std::fixed;
  for (const auto& s : summary) {
    os << "| " << s.condition << " | " << s.method << " | " << s.found << "/" << s.images << " ("
       << std::setprecision(1) << 100.0 * s.found / std::max(1, s.images) << " %) | " << std::setprecision(3)
       << s.median_mm << " | " << s.p95_mm << " | " << s.max_mm << " | " << s.median_deg << " | " << s.max_deg
       << " | " << std::setprecision(1) << s.median_ms << " |";
    if (decoys) os << " " << s.false_positives << "/" << s.decoys << " |";
    os << "\n";
  }
  os << std::setprecision(0) << "\nMarker " << config.marker << ", camera " << config.camera << ", net " << config.net
     << ", tilt " << config.tilt_from << ".." << config.tilt_to << " step " << config.tilt_step << " deg, pan "
     << config.pan_from << ".." << config.pan_to << " step " << config.pan_step << " deg, supersampling "
     << config.supersampling << ", seed " << config.seed << ". Conditions (drawn per view; illumination log-uniform):\n";
  for (const auto& c : config.conditions) {
    auto span = [&](double lo, double hi, int precision) {
      std::ostringstream t;
      t << std::fixed << std::setprecision(precision) << lo;
      if (hi != lo) t << ".." << hi;
      return t.str();
    };
    os << "- " << c.name << ": distance " << span(c.distance_min, c.distance_max, 2) << " m, blur "
       << span(c.blur_min, c.blur_max, 1) << " px, noise " << span(c.noise_min, c.noise_max, 0) << ", illumination "
       << span(c.illumination_min, c.illumination_max, 2) << ", wall " << span(c.background, c.background, 2)
       << (c.reflection ? ", a specular highlight near the marker" : "") << "\n";
  }
  return os.str();
}

std::string sideBySideMarkdown(const std::vector<StudySummaryRow>& summary) {
  const bool decoys = anyDecoys(summary);
  std::ostringstream os;
  os << "| condition | ours | detected: ours / apriltag | median mm: ours / apriltag | p95 mm: ours / apriltag | "
        "rate >= apriltag | median <= apriltag / 2 |"
     << (decoys ? " false positives on decoys: ours / apriltag |\n" : "\n");
  os << "|---|---|---|---|---|---|---|" << (decoys ? "---|\n" : "\n");
  os << std::fixed;
  for (const auto& t : checkTargets(summary)) {
    const StudySummaryRow& d = *findSummary(summary, t.condition, t.method);
    const StudySummaryRow& a = *findSummary(summary, t.condition, "apriltag");
    auto rate = [](const StudySummaryRow& s) {
      std::ostringstream r;
      r << std::fixed << std::setprecision(1) << 100.0 * s.found / std::max(1, s.images) << " %";
      return r.str();
    };
    os << "| " << t.condition << " | " << t.method << " | " << rate(d) << " / " << rate(a) << " | "
       << std::setprecision(3) << d.median_mm << " / " << a.median_mm << " | " << d.p95_mm << " / " << a.p95_mm
       << " | " << (t.rate_ok ? "yes" : "NO") << " | " << (t.median_ok ? "yes" : "NO") << " |";
    if (decoys) os << " " << d.false_positives << "/" << d.decoys << " / " << a.false_positives << "/" << a.decoys << " |";
    os << "\n";
  }
  return os.str();
}

namespace {

// The error map's colours: a logarithmic scale from 0.01 mm to `scale_mm` (at least 0.1 mm).
class LogColourScale {
 public:
  explicit LogColourScale(double scale_mm) : hi_(std::max(scale_mm, 10 * kLo)) {
    cv::Mat ramp(256, 1, CV_8UC1);
    for (int i = 0; i < 256; ++i) ramp.at<uchar>(i) = static_cast<uchar>(i);
    cv::applyColorMap(ramp, colours_, cv::COLORMAP_VIRIDIS);
  }
  static constexpr double kLo = 0.01;  // mm: the bottom of the scale
  double hi() const { return hi_; }
  double level(double mm) const { return (std::log10(std::max(mm, kLo)) - std::log10(kLo)) / (std::log10(hi_) - std::log10(kLo)); }
  cv::Scalar colour(double mm) const {
    const int i = std::max(0, std::min(255, static_cast<int>(std::lround(255.0 * level(mm)))));
    const cv::Vec3b c = colours_.at<cv::Vec3b>(i);
    return cv::Scalar(c[0], c[1], c[2]);
  }

 private:
  double hi_;
  cv::Mat colours_;
};

const auto kFont = cv::FONT_HERSHEY_SIMPLEX;
const int kCell = 24, kLeft = 50, kTop = 40, kGap = 70;

void label(cv::Mat& img, const std::string& text, cv::Point at, double scale, const cv::Scalar& colour = cv::Scalar(0, 0, 0)) {
  cv::putText(img, text, at, kFont, scale, colour, 1, cv::LINE_AA);
}

// One method's panel at y0: a cell per view coloured by its error (grey with a red cross: not
// found), the tilt and pan axes.
void drawPanel(cv::Mat& img, const std::vector<StudyRow>& rows, const std::string& condition, const std::string& method,
               const std::vector<double>& pans, const std::vector<double>& tilts, int y0, const LogColourScale& scale) {
  const int panel_w = static_cast<int>(pans.size()) * kCell, panel_h = static_cast<int>(tilts.size()) * kCell;
  label(img, method, cv::Point(kLeft, y0 - 6), 0.5);
  for (const auto& r : rows) {
    if (r.condition != condition || r.method != method || r.decoy) continue;
    const int cx = static_cast<int>(std::find(pans.begin(), pans.end(), r.pan) - pans.begin());
    const int cy = static_cast<int>(std::find(tilts.begin(), tilts.end(), r.tilt) - tilts.begin());
    const cv::Rect box(kLeft + cx * kCell, y0 + cy * kCell, kCell, kCell);
    if (r.found) {
      cv::rectangle(img, box, scale.colour(r.position_error_mm), cv::FILLED);
    } else {
      cv::rectangle(img, box, cv::Scalar(160, 160, 160), cv::FILLED);
      cv::line(img, box.tl(), box.br() - cv::Point(1, 1), cv::Scalar(0, 0, 255), 1);
      cv::line(img, cv::Point(box.x, box.y + kCell - 1), cv::Point(box.x + kCell - 1, box.y), cv::Scalar(0, 0, 255), 1);
    }
  }
  cv::rectangle(img, cv::Rect(kLeft, y0, panel_w, panel_h), cv::Scalar(0, 0, 0), 1);
  for (size_t t = 0; t < tilts.size(); ++t) {
    std::ostringstream s;
    s << tilts[t];
    label(img, s.str(), cv::Point(kLeft - 20, y0 + static_cast<int>(t) * kCell + 16), 0.35);
  }
  for (size_t p = 0; p < pans.size(); p += std::max<size_t>(1, pans.size() / 12)) {
    std::ostringstream s;
    s << pans[p];
    label(img, s.str(), cv::Point(kLeft + static_cast<int>(p) * kCell + 2, y0 + panel_h + 14), 0.35);
  }
  label(img, "pan [deg] ->", cv::Point(kLeft + panel_w - 90, y0 + panel_h + 30), 0.4);
  label(img, "tilt", cv::Point(kLeft - 45, y0 + panel_h / 2 + 4), 0.35);
}

// The colour bar at (bx, by), bh high, with a tick per decade and at the top of the scale.
void drawColourBar(cv::Mat& img, int bx, int by, int bh, const LogColourScale& scale) {
  const double lo = LogColourScale::kLo, hi = scale.hi();
  for (int i = 0; i < bh; ++i) {
    const double mm = lo * std::pow(hi / lo, i / (bh - 1.0));
    cv::line(img, cv::Point(bx, by + bh - 1 - i), cv::Point(bx + 16, by + bh - 1 - i), scale.colour(mm), 1);
  }
  cv::rectangle(img, cv::Rect(bx, by, 17, bh), cv::Scalar(0, 0, 0), 1);
  std::vector<double> ticks;
  for (double t = lo; t <= hi * 1.0001; t *= 10) ticks.push_back(t);
  if (hi / ticks.back() > 1.5) ticks.push_back(hi);
  for (double t : ticks) {
    std::ostringstream s;
    s << (t < 0.1 ? std::setprecision(2) : std::setprecision(t < 1 ? 1 : 0)) << std::fixed << t;
    if (t == hi) s << "+";
    const int y = by + bh - 1 - static_cast<int>(std::lround(scale.level(t) * (bh - 1)));
    cv::line(img, cv::Point(bx + 17, y), cv::Point(bx + 21, y), cv::Scalar(0, 0, 0), 1);
    label(img, s.str(), cv::Point(bx + 24, y + 4), 0.35);
  }
  label(img, "mm (log)", cv::Point(bx - 5, by - 6), 0.35);
  label(img, "x = not found", cv::Point(bx - 5, by + bh + 20), 0.35, cv::Scalar(0, 0, 255));
}

}  // namespace

cv::Mat errorMapImage(const std::vector<StudyRow>& rows, const std::string& condition, double scale_mm) {
  std::vector<double> pans, tilts;
  std::vector<std::string> methods;
  for (const auto& r : rows) {
    if (r.condition != condition || r.decoy) continue;
    if (std::find(pans.begin(), pans.end(), r.pan) == pans.end()) pans.push_back(r.pan);
    if (std::find(tilts.begin(), tilts.end(), r.tilt) == tilts.end()) tilts.push_back(r.tilt);
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  std::sort(pans.begin(), pans.end());
  std::sort(tilts.begin(), tilts.end());
  const int bar = 80;
  const int panel_w = static_cast<int>(pans.size()) * kCell, panel_h = static_cast<int>(tilts.size()) * kCell;
  const int width = std::max(460, kLeft + panel_w + bar + 40);
  const int height = kTop + 20 + static_cast<int>(methods.size()) * (panel_h + kGap) + 10;
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const LogColourScale scale(scale_mm);
  label(img, "position error [mm], condition " + condition, cv::Point(kLeft, 22), 0.6);
  for (size_t m = 0; m < methods.size(); ++m) {
    drawPanel(img, rows, condition, methods[m], pans, tilts, kTop + 20 + static_cast<int>(m) * (panel_h + kGap), scale);
  }
  drawColourBar(img, kLeft + panel_w + 20, kTop + 20, std::max(120, panel_h * 2), scale);
  return img;
}

}  // namespace marker
}  // namespace imagenets
